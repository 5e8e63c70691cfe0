# cmake -DTOOL=<sm_coverage> -DDATA=<this folder> -DOUT=<scratch folder> -P check_report.cmake
# Known answer of tiny_a.dat + tiny_b.dat (hand-counted from the two files):
#   sm_a line: block (u0 5), if (0 in both instances), else (3), case (test 2, another
#     hierarchy and parameter set sm_a__W8: 1) -> 3/4 = 75 %
#   sm_a toggle: x[0] 1 (one edge), x[1] 2, x[2] 1 in u0 and 1 in u1 (no instance saw both
#     edges), x[3] 0 in test 1 and 1 in test 2 (sm_a__W8), y 7 -> 2/5 = 40 %
#   sm_b line 1/1; toggle z[0] 5, z[1] 0, z[2] 1 + 2 (the same point in both files) -> 2/3
#   total: line 4/5 = 80 %, toggle 4/8 = 50 %; the v_user point is ignored
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})
set(errors 0)
function(expect what got want)
  if(NOT "${got}" STREQUAL "${want}")
    message(SEND_ERROR "${what}: got '${got}', want '${want}'")
  endif()
endfunction()

execute_process(COMMAND ${TOOL} ${DATA}/tiny_a.dat ${DATA}/tiny_b.dat --json ${OUT}/c.json
                        --line-dat ${OUT}/line.dat --toggle-dat ${OUT}/toggle.dat
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
expect("exit code" "${rc}" "0")
message(STATUS "${out}")
file(READ ${OUT}/c.json j)
foreach(c "sm_a;line;4;3;75.0" "sm_a;toggle;5;2;40.0" "sm_b;line;1;1;100.0" "sm_b;toggle;3;2;66.67")
  list(GET c 0 m)
  list(GET c 1 k)
  list(GET c 2 points)
  list(GET c 3 covered)
  list(GET c 4 pct)
  string(JSON v GET "${j}" modules ${m} ${k} points)
  expect("${m} ${k} points" "${v}" "${points}")
  string(JSON v GET "${j}" modules ${m} ${k} covered)
  expect("${m} ${k} covered" "${v}" "${covered}")
  # the percent as the tool wrote it (CMake's own JSON parser prints 66.67 as 66.670000000000002)
  string(REPLACE "." "[.]" p "${pct}")
  set(skip "")
  if(k STREQUAL "toggle")
    set(skip "}[^}]*")  # past the line object
  endif()
  if(NOT j MATCHES "\"${m}\": {[^}]*${skip}\"${k}\": {[^}]*\"percent\": ${p}\n")
    message(SEND_ERROR "${m} ${k} percent: want ${pct} in\n${j}")
  endif()
endforeach()
string(JSON v GET "${j}" modules sm_a file)
expect("sm_a file" "${v}" "/rtl/sm_a.v")
string(JSON v GET "${j}" modules sm_a below_goal)
expect("sm_a below goal" "${v}" "ON")
if(NOT j MATCHES "\"total\": {[^}]*\"line\": {[^}]*\"percent\": 80[.]0\n[^}]*}[^}]*\"toggle\": {[^}]*\"percent\": 50[.]0\n")
  message(SEND_ERROR "total: want line 80.0 and toggle 50.0 in\n${j}")
endif()
string(JSON v GET "${j}" ignored_points)
expect("ignored points" "${v}" "1")
string(JSON n LENGTH "${j}" modules)
expect("modules" "${n}" "2")
# the console table has the same numbers
if(NOT out MATCHES "sm_a +3/4 +75.0 +2/5 +40.0  below goal" OR NOT out MATCHES "all +4/5 +80.0 +4/8 +50.0")
  message(SEND_ERROR "console table:\n${out}")
endif()
# the split files: the line and branch points, the toggle points, counts summed over files
file(READ ${OUT}/line.dat l)
file(READ ${OUT}/toggle.dat t)
string(REGEX MATCHALL "\n" nl "${l}")
string(REGEX MATCHALL "\n" nt "${t}")
list(LENGTH nl nl)
list(LENGTH nt nt)
expect("line.dat lines" "${nl}" "10")  # header + 8 points of test 1 + 1 of test 2
expect("toggle.dat lines" "${nt}" "11")  # header + 9 of test 1 + x[3] of test 2 (z[2] summed)
if(NOT t MATCHES "z\\[2\\][^\n]*' 3\n")
  message(SEND_ERROR "toggle.dat: want z[2] with the count 3 in\n${t}")
endif()
if(l MATCHES "v_toggle|v_user" OR t MATCHES "v_line|v_branch|v_user")
  message(SEND_ERROR "line.dat or toggle.dat holds points of another kind")
endif()
# threshold: at --toggle-min 1 every toggle point of sm_a with a count > 0 is covered
execute_process(COMMAND ${TOOL} ${DATA}/tiny_a.dat ${DATA}/tiny_b.dat --toggle-min 1 --json ${OUT}/c1.json
                RESULT_VARIABLE rc OUTPUT_QUIET)
expect("exit code --toggle-min 1" "${rc}" "0")
file(READ ${OUT}/c1.json j)
string(JSON v GET "${j}" modules sm_a toggle covered)
expect("sm_a toggle covered at --toggle-min 1" "${v}" "5")

# bad input: one error line, exit code 1
execute_process(COMMAND ${TOOL} ${DATA}/bad_count.dat RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
expect("bad count: exit code" "${rc}" "1")
expect("bad count: message" "${err}" "sm_coverage: error: ${DATA}/bad_count.dat:2: bad count ' 5x'\n")
execute_process(COMMAND ${TOOL} ${DATA}/check_report.cmake RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
expect("not a coverage file: exit code" "${rc}" "1")
if(NOT err MATCHES "^sm_coverage: error: .*check_report.cmake: not a Verilator coverage file")
  message(SEND_ERROR "not a coverage file: ${err}")
endif()
