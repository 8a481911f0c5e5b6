// Everything in the public API.
#pragma once
#include "deltamesh/delaunay.hpp"
#include "deltamesh/errors.hpp"
#include "deltamesh/geometry.hpp"
#include "deltamesh/mesh.hpp"
#include "deltamesh/predicates.hpp"
#include "deltamesh/pslg.hpp"
#include "deltamesh/svg.hpp"
#include "deltamesh/triangle_io.hpp"
#include "deltamesh/validate.hpp"
#include "deltamesh/version.hpp"
