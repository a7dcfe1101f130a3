#!/usr/bin/env python3
"""Compare two write_dump files of bench/scenes/in.force_dump atom by atom (sorted by id):
prints how many values differ and the largest relative difference; exit 1 if any differ."""
import sys


def load(path):
    lines = open(path).read().split("ITEM: ATOMS")[1].strip().splitlines()
    return {int(l.split()[0]): [float(v) for v in l.split()[1:]] for l in lines[1:]}


def main():
    a, b = load(sys.argv[1]), load(sys.argv[2])
    if a.keys() != b.keys():
        sys.exit("compare_dumps: the dumps hold different atoms")
    worst, differing = 0.0, 0
    for k in a:
        for x, y in zip(a[k], b[k]):
            if x != y:
                differing += 1
                worst = max(worst, abs(x - y) / max(abs(x), abs(y)))
    total = sum(len(v) for v in a.values())
    print(f"{differing} of {total} values differ, largest relative difference {worst:.3g}")
    sys.exit(1 if differing else 0)


if __name__ == "__main__":
    main()
