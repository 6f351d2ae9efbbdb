# ctest driver: generate one preset with the forest CLI (with -DBAKE=1 also bake it: hull,
# tables, impostor), then run the Khronos glTF-Validator on it. Any error or warning fails
# the test.
# Usage: cmake -DFOREST=<exe> -DNODE=<node> -DSCRIPT=validate_gltf.mjs -DSPECIES=<toml>
#              -DOUT=<glb> -DMODULES=<dir with node_modules/gltf-validator> -P validate_gltf.cmake
foreach(var FOREST NODE SCRIPT SPECIES OUT MODULES)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "validate_gltf.cmake: -D${var}=... is required")
  endif()
endforeach()
if(NOT EXISTS "${MODULES}/gltf-validator")
  message(FATAL_ERROR "validate_gltf.cmake: ${MODULES}/gltf-validator is missing; run "
                      "`cp tests/tools/package*.json <build>/npm/ && npm ci` in <build>/npm")
endif()

file(REMOVE "${OUT}")
execute_process(
  COMMAND "${FOREST}" generate --species "${SPECIES}" --seed 7 --out "${OUT}"
  RESULT_VARIABLE gen_rc)
if(NOT gen_rc EQUAL 0)
  message(FATAL_ERROR "forest generate failed (${gen_rc}) for ${SPECIES}")
endif()
if(NOT EXISTS "${OUT}")
  message(FATAL_ERROR "forest generate succeeded but wrote no ${OUT}")
endif()
if(BAKE)
  execute_process(COMMAND "${FOREST}" bake "${OUT}" --views 1 --resolution 32 RESULT_VARIABLE bake_rc)
  if(NOT bake_rc EQUAL 0)
    message(FATAL_ERROR "forest bake failed (${bake_rc}) for ${OUT}")
  endif()
endif()

execute_process(
  COMMAND "${CMAKE_COMMAND}" -E env "NODE_PATH=${MODULES}" "${NODE}" "${SCRIPT}" "${OUT}"
  RESULT_VARIABLE val_rc)
if(NOT val_rc EQUAL 0)
  message(FATAL_ERROR "glTF-Validator reported problems in ${OUT} (exit ${val_rc})")
endif()
