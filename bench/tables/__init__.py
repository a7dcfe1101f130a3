"""The tables of bench/run_bench.py, one module each, and the LAMMPS runs they share."""
