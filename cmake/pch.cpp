// Compiles cmake/modules.cmake's precompiled headers (vilslam_pch) once for every target that reuses them.
