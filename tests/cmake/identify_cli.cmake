# Command-line tests of `plateball identify`: the fit of the example tracks (tests/data, made by
# `plateball simulate` with seeded noise, see their header lines), the fitted problem read back by
# simulate, exit codes and messages of bad tracks. Uses plateball_cli_test() from cli_tests.cmake.
if(NOT TARGET plateball_cli OR NOT COMMAND plateball_cli_test)
  return()
endif()

plateball_cli_test(identify.help 0 REGEX "--svg.*--radius" -- identify --help)
# lambda = 1.3, mu = 4 (period pi), noise 0.005 on 301 samples: lambda to ~1e-3, the period to ~3e-3.
plateball_cli_test(identify.track 0 --number period 3.141592653589793 0.02
  REGEX "\"status\": \"identified\".*\"lambda\": 1\\.30.*\"fitted_problem\""
  -- identify tests/data/identify_track.csv)
# The track's true period is pi (mu = 4); the fit's standard error of the period is 0.057 (from
# mu's 0.153 at mu = 4.16): three standard errors.
plateball_cli_test(identify.track_json_with_sigma 0 --number period 3.141592653589793 0.17
  REGEX "\"status\": \"identified\".*\"sigma_estimated\": false"
  -- identify tests/data/identify_track.json)
plateball_cli_test(identify.svg 0 REGEX "<svg.*fitted free motion.*residuals, rms"
  --cat ${CMAKE_CURRENT_BINARY_DIR}/cli_identify.svg
  -- identify tests/data/identify_track.csv --no-profile --out ${CMAKE_CURRENT_BINARY_DIR}/cli_identify.json
     --svg ${CMAKE_CURRENT_BINARY_DIR}/cli_identify.svg)
# The straight track of problems/simulate_example.json (v0 = 0): mu = 1 (period 2 pi) is fitted,
# lambda is reported as not identified (exit 0: the fit itself is a result), no fitted_problem.
plateball_cli_test(identify.straight_track_does_not_identify_lambda 0 --number period 6.283185307179586 0.01
  REGEX "\"status\": \"lambda_not_identified\".*\"usable\": false.*lambda not identified"
  -- identify tests/data/identify_straight.csv)

# Bad tracks: exit 3 naming the row, 4 when no free motion fits, 5 for a missing file.
set(dir ${CMAKE_CURRENT_BINARY_DIR}/identify_tracks)
file(MAKE_DIRECTORY ${dir})
set(head "t,x,y\n")
set(rows "")
foreach(i RANGE 0 9)
  string(APPEND rows "${i},0.${i},0\n")
endforeach()
file(WRITE ${dir}/unsorted.csv "${head}0,0,0\n1,1,0\n3,3,0\n2,2,0\n4,4,0\n5,5,0\n6,6,0\n7,7,0\n8,8,0\n")
file(WRITE ${dir}/duplicate.csv "${head}0,0,0\n1,1,0\n1,2,0\n3,3,0\n4,4,0\n5,5,0\n6,6,0\n7,7,0\n8,8,0\n")
file(WRITE ${dir}/nan.csv "${head}0,0,0\n1,1,0\n2,nan,0\n3,3,0\n4,4,0\n5,5,0\n6,6,0\n7,7,0\n8,8,0\n")
file(WRITE ${dir}/text.csv "${head}0,0,0\n1,one,0\n")
file(WRITE ${dir}/few.csv "${head}0,0,0\n1,1,0\n2,2,0\n")
file(WRITE ${dir}/column.csv "t,x,y,speed\n0,0,0,1\n")
file(WRITE ${dir}/sigma.csv "t,x,y,sigma\n${rows}")
file(WRITE ${dir}/negative_sigma.csv "t,x,y,sigma\n0,0,0,0.1\n1,1,0,0.1\n2,2,0,0.1\n3,3,0,-1\n4,4,0,0.1\n5,5,0,0.1\n6,6,0,0.1\n7,7,0,0.1\n8,8,0,0.1\n")
# A zigzag: the contact point reverses every 10 samples, which no free motion does.
set(zigzag "${head}")
foreach(i RANGE 0 59)
  math(EXPR leg "(${i} / 10) % 2")
  math(EXPR k "${i} % 10")
  if(leg EQUAL 0)
    string(APPEND zigzag "${i},${k},0\n")
  else()
    math(EXPR back "10 - ${k}")
    string(APPEND zigzag "${i},${back},0\n")
  endif()
endforeach()
file(WRITE ${dir}/zigzag.csv "${zigzag}")
plateball_cli_test(identify.unsorted 3 REGEX "unsorted.csv: t\\[3\\]: value 2: times must be strictly increasing" -- identify ${dir}/unsorted.csv)
plateball_cli_test(identify.duplicate 3 REGEX "t\\[2\\]: value 1: duplicate time" -- identify ${dir}/duplicate.csv)
plateball_cli_test(identify.nan 3 REGEX "x\\[2\\]: value nan: must be finite" -- identify ${dir}/nan.csv)
plateball_cli_test(identify.not_a_number 3 REGEX "x\\[1\\]: value \"one\": not a number" -- identify ${dir}/text.csv)
plateball_cli_test(identify.too_few 3 REGEX "t \\(rows\\): value 3: too few samples" -- identify ${dir}/few.csv)
plateball_cli_test(identify.unknown_column 3 REGEX "header column 3: value \"speed\": unknown column" -- identify ${dir}/column.csv)
plateball_cli_test(identify.cells 3 REGEX "row\\[0\\]: value 3 cells: must have 4 cells" -- identify ${dir}/sigma.csv)
plateball_cli_test(identify.negative_sigma 3 REGEX "sigma\\[3\\]: value -1: must be finite and > 0" -- identify ${dir}/negative_sigma.csv)
plateball_cli_test(identify.no_fit 4 REGEX "\"status\": \"no_fit\".*no free motion fits the track: rms residual" -- identify ${dir}/zigzag.csv)
plateball_cli_test(identify.bad_radius 3 REGEX "--radius: value -2" -- identify tests/data/identify_track.csv --radius -2)
plateball_cli_test(identify.guess_needs_problem 3 REGEX "--guess" -- identify tests/data/identify_track.csv --guess)
plateball_cli_test(identify.missing_file 5 -- identify tests/data/no_such_track.csv)

# Eight flights of the circle plan (lambda = 2, mu = 1) between known impulses, noise 0.002
# (tests/data/identify_impulses_track.csv, its header): lambda to ~3e-3, each delta psi fitted.
set(impulses "1.97971051947,4.11910028592,5.93450695524,7.6917274569,9.76605547974,11.8431439933,13.6016943332")
plateball_cli_test(identify.impulses 0
  REGEX "\"status\": \"identified\".*\"lambda\": 2\\.00.*\"impulses\": \\[.*\"delta_psi\": 0\\.74.*\"delta_psi\\[6\\]\""
  -- identify tests/data/identify_impulses_track.csv --impulses ${impulses} --no-profile)
plateball_cli_test(identify.impulses_svg 0 REGEX "<svg.*fitted free flights between the impulses"
  --cat ${CMAKE_CURRENT_BINARY_DIR}/cli_identify_impulses.svg
  -- identify tests/data/identify_impulses_track.csv --impulses ${impulses} --no-profile --out ${dir}/impulses.json
     --svg ${CMAKE_CURRENT_BINARY_DIR}/cli_identify_impulses.svg)
file(WRITE ${dir}/impulses_unsorted.json "{\"t\": [0,1,2,3,4,5,6,7,8,9,10,11,12,13,14,15], \"x\": [[0,0],[1,0],[2,0],[3,0],[4,0],[5,0],[6,0],[7,0],[8,0],[9,0],[10,0],[11,0],[12,0],[13,0],[14,0],[15,0]], \"impulse_times\": [9.5, 4.5]}")
plateball_cli_test(identify.impulses_unsorted 3 REGEX "impulses_unsorted.json: impulse_times\\[1\\]: value 4.5: impulse times must be strictly increasing"
  -- identify ${dir}/impulses_unsorted.json)
plateball_cli_test(identify.impulses_outside 3 REGEX "command line: --impulses\\[0\\]: value 99: must be inside the track"
  -- identify tests/data/identify_track.csv --impulses 99)
plateball_cli_test(identify.impulses_few_samples 3 REGEX "command line: --impulses\\[1\\]: value 0.55: too few samples in the flight before it: 1"
  -- identify tests/data/identify_impulses_track.csv --impulses 0.5,0.55)
plateball_cli_test(identify.impulses_twice 3 REGEX "--impulses.*impulse_times already"
  -- identify ${dir}/impulses_unsorted.json --impulses 3)

# A measured axial spin (tests/data/identify_spin_track.csv, lambda = 1: a straight contact path):
# the spin shows v0 != 0, so lambda = 1 is identified; the positions alone are not enough.
plateball_cli_test(identify.spin 0
  REGEX "\"spin_given\": true.*\"status\": \"identified\".*\"lambda\": 1\\.00.*\"spin\": {"
  -- identify tests/data/identify_spin_track.csv --no-profile)
string(REPLACE "\n" ",1\n" spin_rows "${rows}")
file(WRITE ${dir}/spin_without_sigma.csv "t,x,y,spin\n${spin_rows}")
plateball_cli_test(identify.spin_needs_its_sigma 3 REGEX "sigma_spin \\(rows\\): value 0: must have one row per time \\(10\\): a measured spin needs its noise"
  -- identify ${dir}/spin_without_sigma.csv)

# Measured orientations and body rates on a flight of 0.15 period (tests/data/identify_orientation_track.csv
# and identify_imu_track.csv, their headers: lambda = 1.3, noise 0.002): lambda identified (1.317 +- 0.014
# and 1.2993 +- 0.0014), the frame fitted (chi), the orientation in fitted_problem.
plateball_cli_test(identify.orientation 0
  REGEX "\"orientation_given\": true.*\"status\": \"identified\".*\"lambda\": 1\\.3.*\"chi\".*\"orientation\": \\[.*\"orientation\": {[^}]*\"rms\".*\"orientation\": {[^}]*\"quaternion\""
  -- identify tests/data/identify_orientation_track.csv)
plateball_cli_test(identify.body_rate 0
  REGEX "\"body_rate_given\": true.*\"status\": \"identified\".*\"lambda\": 1\\.29.*\"body_rate\": {[^}]*\"rms\""
  -- identify tests/data/identify_imu_track.csv --no-profile)
plateball_cli_test(identify.orientation_svg 0 REGEX "<svg.*residuals, rms.*orientation residuals, rms"
  --cat ${CMAKE_CURRENT_BINARY_DIR}/cli_identify_orientation.svg
  -- identify tests/data/identify_orientation_track.csv --no-profile --out ${dir}/orientation.json
     --svg ${CMAKE_CURRENT_BINARY_DIR}/cli_identify_orientation.svg)
# The same body-rate track as JSON ("body_rate": [[wx, wy, wz], ...]): the same fit to the last digit.
plateball_cli_test(identify.body_rate_json 0 REGEX "\"body_rate_given\": true.*\"lambda\": 1\\.2992705109732285,"
  -- identify tests/data/identify_imu_track.json --no-profile)
# Bad orientation and body-rate columns: exit 3 naming the column and the row.
set(q_rows "")
set(w_rows "")
set(sw_rows "")
foreach(i RANGE 0 9)
  if(i EQUAL 3)
    string(APPEND q_rows "${i},0.${i},0,0.5,0,0,0\n")
  else()
    string(APPEND q_rows "${i},0.${i},0,1,0,0,0\n")
  endif()
  string(APPEND w_rows "${i},0.${i},0,0.1,0,0,1\n")
  string(APPEND sw_rows "${i},0.${i},0,0.1,1,0.1,0,0,1,0.1\n")
endforeach()
file(WRITE ${dir}/quaternion_norm.csv "t,x,y,qw,qx,qy,qz\n${q_rows}")
string(REPLACE "2,0.2,0,1,0,0,0" "2,0.2,0,1,nan,0,0" q_nan "${q_rows}")
file(WRITE ${dir}/quaternion_nan.csv "t,x,y,qw,qx,qy,qz\n${q_nan}")
file(WRITE ${dir}/quaternion_mixed.csv "t,x,y,qw,qx,qy\n0,0,0,1,0,0\n")
file(WRITE ${dir}/rate_without_sigma.csv "t,x,y,sigma,wx,wy,wz\n${w_rows}")
file(WRITE ${dir}/spin_and_rate.csv "t,x,y,sigma,spin,sigma_spin,wx,wy,wz,sigma_body_rate\n${sw_rows}")
file(WRITE ${dir}/quaternion_short.json "{\"t\": [0,1,2,3,4,5,6,7], \"x\": [[0,0],[1,0],[2,0],[3,0],[4,0],[5,0],[6,0],[7,0]], \"orientation\": [[1,0,0,0],[1,0,0]]}")
plateball_cli_test(identify.quaternion_not_unit 3
  REGEX "quaternion_norm.csv: orientation\\[3\\]: value \\[0.5, 0, 0, 0\\]: not a unit quaternion \\(w, x, y, z\\): norm 0.5, allowed 1 \\+- 1e-05"
  -- identify ${dir}/quaternion_norm.csv)
plateball_cli_test(identify.quaternion_nan 3 REGEX "orientation\\[2\\].x: value nan: must be finite" -- identify ${dir}/quaternion_nan.csv)
plateball_cli_test(identify.quaternion_mixed_columns 3
  REGEX "header column qz: value \\(missing\\): column qw is given: an orientation is the unit quaternion qw, qx, qy, qz"
  -- identify ${dir}/quaternion_mixed.csv)
plateball_cli_test(identify.body_rate_needs_its_sigma 3
  REGEX "sigma_body_rate \\(rows\\): value 0: must have one row per time \\(10\\): measured body rates need their noise"
  -- identify ${dir}/rate_without_sigma.csv)
plateball_cli_test(identify.spin_and_body_rate 3 REGEX "body_rate \\(rows\\): value 10: give either spin or body_rate, not both"
  -- identify ${dir}/spin_and_rate.csv)
plateball_cli_test(identify.quaternion_json_row 3 REGEX "quaternion_short.json: orientation\\[1\\]: value \\[1,0,0\\]: must be a unit quaternion \\[w, x, y, z\\]"
  -- identify ${dir}/quaternion_short.json)

# The fitted problem is a problem file: simulate reads it back and moves at the fitted period.
if(EXISTS /usr/bin/python3)
  add_test(NAME cli.identify.fitted_problem_is_a_problem_file
    COMMAND /usr/bin/python3 -c "
import json, subprocess, sys
exe, out = sys.argv[1], sys.argv[2]
doc = json.loads(subprocess.run([exe, 'identify', 'tests/data/identify_track.csv', '--no-profile'], check=True, capture_output=True, text=True).stdout)
json.dump(doc['fitted_problem'], open(out, 'w'))
sim = json.loads(subprocess.run([exe, 'simulate', out, '--samples', '2'], check=True, capture_output=True, text=True).stdout)
assert abs(sim['period'] - doc['fit']['period']) < 1e-12 and sim['model']['lambda'] == doc['fit']['lambda'], (sim['period'], doc['fit'])
print('fitted problem read back: period', sim['period'])
" $<TARGET_FILE:plateball_cli> ${dir}/fitted_problem.json
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  set_tests_properties(cli.identify.fitted_problem_is_a_problem_file PROPERTIES TIMEOUT 120 LABELS cli
                       PASS_REGULAR_EXPRESSION "fitted problem read back")
  # With orientations the fitted problem carries the fitted frame: simulate starts from it.
  add_test(NAME cli.identify.fitted_orientation_is_the_problem_start
    COMMAND /usr/bin/python3 -c "
import json, subprocess, sys
exe, out = sys.argv[1], sys.argv[2]
doc = json.loads(subprocess.run([exe, 'identify', 'tests/data/identify_orientation_track.csv', '--no-profile'], check=True, capture_output=True, text=True).stdout)
json.dump(doc['fitted_problem'], open(out, 'w'))
sim = json.loads(subprocess.run([exe, 'simulate', out, '--samples', '2'], check=True, capture_output=True, text=True).stdout)
w, x, y, z = doc['fit']['orientation']
a = [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]
err = max(abs(a[i][j] - sim['initial']['orientation'][i][j]) for i in range(3) for j in range(3))
assert err < 1e-12, err
print('fitted orientation read back: largest entry difference', err)
" $<TARGET_FILE:plateball_cli> ${dir}/fitted_orientation_problem.json
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  set_tests_properties(cli.identify.fitted_orientation_is_the_problem_start PROPERTIES TIMEOUT 120 LABELS cli
                       PASS_REGULAR_EXPRESSION "fitted orientation read back")
endif()
