cmake_minimum_required(VERSION 3.20)
# Runs cmake/float_flags.cmake's check on -DFLAGS=... (for the CTest cases in
# tests/CMakeLists.txt): a refusal is a fatal error naming the flag.
include(${CMAKE_CURRENT_LIST_DIR}/../../cmake/float_flags.cmake)
kappa_refuse_contracting_flags("${FLAGS}")
message(STATUS "accepted: ${FLAGS}")
