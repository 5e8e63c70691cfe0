# Synthetic stereo scenes: the sm_scene generator and the default scenes built with the
# project (build/scene: paper configuration 320x240, 128 levels; build/scene_small:
# 64x48, 16 levels for fast system tests). Helper library sm_toolio: toolio/.

add_executable(sm_scene ${CMAKE_CURRENT_LIST_DIR}/sm_scene.cpp)
target_link_libraries(sm_scene PRIVATE sm_toolio CLI11::CLI11)
target_compile_options(sm_scene PRIVATE ${SM_WARNINGS})

set(SM_SCENE_DIR ${CMAKE_BINARY_DIR}/scene CACHE INTERNAL "default synthetic scene (320x240, 128 levels)")
set(SM_SCENE_SMALL_DIR ${CMAKE_BINARY_DIR}/scene_small CACHE INTERNAL "small synthetic scene (64x48, 16 levels)")
set(SM_SCENE_VGA_DIR ${CMAKE_BINARY_DIR}/scene_vga CACHE INTERNAL "640x480 synthetic scene (128 levels)")
set(_sm_scene_files left.png right.png gt.png nonocc.png scale.txt camera.json calib.json)
list(TRANSFORM _sm_scene_files PREPEND ${SM_SCENE_DIR}/ OUTPUT_VARIABLE _sm_scene_out)
list(TRANSFORM _sm_scene_files PREPEND ${SM_SCENE_SMALL_DIR}/ OUTPUT_VARIABLE _sm_scene_small_out)
list(TRANSFORM _sm_scene_files PREPEND ${SM_SCENE_VGA_DIR}/ OUTPUT_VARIABLE _sm_scene_vga_out)
add_custom_command(OUTPUT ${_sm_scene_out}
  COMMAND sm_scene --width 320 --height 240 --levels 128 --seed 1 --objects 6 --out ${SM_SCENE_DIR}
  DEPENDS sm_scene COMMENT "Generating the default stereo scene (320x240, 128 levels)")
add_custom_command(OUTPUT ${_sm_scene_small_out}
  COMMAND sm_scene --width 64 --height 48 --levels 16 --seed 2 --objects 3 --out ${SM_SCENE_SMALL_DIR}
  DEPENDS sm_scene COMMENT "Generating the small stereo scene (64x48, 16 levels)")
add_custom_command(OUTPUT ${_sm_scene_vga_out}
  COMMAND sm_scene --width 640 --height 480 --levels 128 --seed 1 --objects 6 --out ${SM_SCENE_VGA_DIR}
  DEPENDS sm_scene COMMENT "Generating the 640x480 stereo scene (128 levels)")
add_custom_target(sm_default_scene ALL DEPENDS ${_sm_scene_out} ${_sm_scene_small_out} ${_sm_scene_vga_out})
