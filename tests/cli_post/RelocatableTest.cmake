# bender-cli is relocatable: copied to a fresh prefix it runs and finds its data in
# <prefix>/share/bender (the install layout) without any source path compiled in; without that
# folder it says so in one line; BENDER_DATA_DIR overrides it.
# Arguments: -DCLI=<bender-cli> -DDATA=<source data folder> -DWORK=<scratch folder>.

file(REMOVE_RECURSE ${WORK})
set(prefix ${WORK}/prefix)
file(MAKE_DIRECTORY ${prefix}/bin ${prefix}/share/bender)
file(COPY ${CLI} DESTINATION ${prefix}/bin)
file(COPY ${DATA}/demo DESTINATION ${prefix}/share/bender)
set(cli ${prefix}/bin/bender-cli)

function(run expected_status)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=BENDER_DATA_DIR ${ARGN}
    RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err
    OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT status EQUAL expected_status)
    message(FATAL_ERROR "${ARGN}: exit ${status}, expected ${expected_status}\n${out}\n${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
  set(err "${err}" PARENT_SCOPE)
endfunction()

run(0 ${cli} --help)
if(NOT out MATCHES "warp")
  message(FATAL_ERROR "bender-cli --help from the prefix printed no command table:\n${out}")
endif()

run(0 ${cli} --data-dir)
get_filename_component(found "${out}" REALPATH)
get_filename_component(expected "${prefix}/share/bender" REALPATH)
if(NOT found STREQUAL expected)
  message(FATAL_ERROR "bender-cli --data-dir: '${out}', expected '${expected}'")
endif()
if(NOT EXISTS "${out}/demo/demo.bender.json")
  message(FATAL_ERROR "the demo plan is not in ${out}/demo")
endif()

# Moved without its data: one clear line, exit 1.
file(MAKE_DIRECTORY ${WORK}/bare/bin)
file(COPY ${CLI} DESTINATION ${WORK}/bare/bin)
run(1 ${WORK}/bare/bin/bender-cli --data-dir)
if(NOT err MATCHES "BENDER_DATA_DIR")
  message(FATAL_ERROR "no data folder: unclear message '${err}'")
endif()

# BENDER_DATA_DIR wins over the executable's location.
execute_process(COMMAND ${CMAKE_COMMAND} -E env BENDER_DATA_DIR=${DATA} ${WORK}/bare/bin/bender-cli
  --data-dir RESULT_VARIABLE status OUTPUT_VARIABLE out OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT status EQUAL 0 OR NOT out STREQUAL DATA)
  message(FATAL_ERROR "BENDER_DATA_DIR=${DATA}: exit ${status}, '${out}'")
endif()
file(REMOVE_RECURSE ${WORK})
