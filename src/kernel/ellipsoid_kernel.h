/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: the engine-independent contact kernel, one query per header (C++17 + Eigen,
   no LAMMPS header, no MPI, no I/O, no exceptions). LAMMPS styles, the LIGGGHTS adapter,
   tests and benchmarks include this.
     ellipsoid_shape.h          the ellipsoid: construction, forms, radii, volumes
     ellipsoid_contact.h        contact of two ellipsoids; the shared result types
     ellipsoid_wang.h           Wang et al. separation test, separating planes
     ellipsoid_plane_contact.h  ellipsoid against a flat wall
     ellipsoid_wall_contact.h   ellipsoid against a wall of any supported shape (dispatch;
                                the shapes' own headers, ellipsoid_box_contact.h, ...)
     ellipsoid_pipeline.h       the per-pair pipeline, its settings and counters
     ellipsoid_pair_history.h   the per-pair history layout (PairHistory)
   ellipsoid_gap.h (the gap function and its minimiser) is internal to the contact and Wang
   queries.
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_ELLIPSOID_KERNEL_H
#define ELLIPSOID_DEP_ELLIPSOID_KERNEL_H

#include "ellipsoid_contact.h"
#include "ellipsoid_pair_history.h"
#include "ellipsoid_pipeline.h"
#include "ellipsoid_plane_contact.h"
#include "ellipsoid_sphere_contact.h"
#include "ellipsoid_cylinder_contact.h"
#include "ellipsoid_cone_contact.h"
#include "ellipsoid_box_contact.h"
#include "ellipsoid_capped_cylinder_contact.h"
#include "ellipsoid_rim_contact.h"
#include "ellipsoid_shape.h"
#include "ellipsoid_wall_contact.h"
#include "ellipsoid_wang.h"

#endif
