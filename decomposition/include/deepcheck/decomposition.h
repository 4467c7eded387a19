#pragma once
// deepcheck::decomposition in one include: triangle meshes, their approximate convex
// decomposition and its on-disk cache.

#include "deepcheck/decomposition/cache.h"
#include "deepcheck/decomposition/cache_file.h"
#include "deepcheck/decomposition/decomposition.h"
#include "deepcheck/decomposition/mesh.h"
#include "deepcheck/decomposition/tolerances.h"
