// The unit that owns a shared precompiled header (cmake/TelearTargets.cmake,
// telear_pch_holder): CMake compiles the header through a target with at least one source.
