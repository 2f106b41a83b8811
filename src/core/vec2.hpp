#pragma once
// Kept for the 2D-only modules: Vec2 is Vec<2> (core/vec.hpp).
#include "core/vec.hpp"
