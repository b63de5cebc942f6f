# The floors of the house: core/ <- accel/ <- stats/ <- renderer/ <- the
# executables and tests. A floor's library sees its own folder and, through
# the libraries it links, the floors below it -- never one above: each folder
# is reached through a directory of its own in the build tree
# (build/floors/NAME/NAME -> the source folder), not through the source
# tree's root, so `#include "renderer/..."` in accel/ does not compile.
# tests/floors/ checks that it does not (ctest: Build.FloorsRefuse*).
function(kappa_floor target folder)
  set(floor_dir ${CMAKE_BINARY_DIR}/floors/${folder})
  file(MAKE_DIRECTORY ${floor_dir})
  file(CREATE_LINK ${CMAKE_SOURCE_DIR}/${folder} ${floor_dir}/${folder} SYMBOLIC)
  target_include_directories(${target} PUBLIC ${floor_dir})
endfunction()
