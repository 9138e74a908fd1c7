// Included first in every reader compiled for fuzzing (CMakeLists.txt says why): toml++'s
// internal assertions off, as in the toml++ library volcomp links.
#pragma once
#define TOML_ASSERT(expr) ((void)0)
