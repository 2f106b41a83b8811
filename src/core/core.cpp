// Anchor translation unit for the header-mostly core library.
#include "core/error.hpp"
#include "core/field2.hpp"
#include "core/grid2.hpp"
#include "core/vec2.hpp"
