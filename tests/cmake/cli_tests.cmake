# Command-line tests of `plateball simulate` and `plateball roll`: exact exit codes (through
# tests/scripts/check_cli.sh), messages (PASS_REGULAR_EXPRESSION) and numbers checked against
# independent values (closed forms) within stated tolerances. The exit code and the numbers are
# checked also when a message is (FAIL_REGULAR_EXPRESSION on check_cli.sh's FAIL lines).
if(NOT TARGET plateball_cli)
  return()
endif()

# plateball_cli_test(NAME EXIT_CODE [REGEX regex] [CHECKS...] -- PLATEBALL_ARGS...)
# CHECKS are check_cli.sh's (--number KEY VALUE TOL, --vector KEY "V1,V2" TOL, --cat FILE).
function(plateball_cli_test name exit_code)
  cmake_parse_arguments(PARSE_ARGV 2 T "" "REGEX" "")
  set(args ${T_UNPARSED_ARGUMENTS})
  list(FIND args "--" sep)
  if(sep EQUAL -1)
    message(FATAL_ERROR "plateball_cli_test(${name}): missing '--' before the arguments")
  endif()
  math(EXPR after "${sep} + 1")
  list(INSERT args ${after} $<TARGET_FILE:plateball_cli>)
  add_test(NAME cli.${name}
           COMMAND bash ${PROJECT_SOURCE_DIR}/tests/scripts/check_cli.sh ${exit_code} ${args}
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  set_tests_properties(cli.${name} PROPERTIES TIMEOUT 120 LABELS cli)
  if(T_REGEX)
    # A pass expression makes ctest ignore the exit status: the script's own verdict (exit code,
    # numbers) must then fail the test through its FAIL lines.
    set_tests_properties(cli.${name} PROPERTIES PASS_REGULAR_EXPRESSION "${T_REGEX}"
                         FAIL_REGULAR_EXPRESSION "check_cli.sh: FAIL")
  endif()
endfunction()

set(pi 3.141592653589793)
set(two_pi 6.283185307179586)

# ---------------------------------------------------------------- help
plateball_cli_test(simulate.help 0 REGEX "--t-end.*--samples" -- simulate --help)
plateball_cli_test(roll.help 0 REGEX "--points.*--segment" -- roll --help)

# ---------------------------------------------------------------- simulate: numbers
# T = 2 pi / sqrt(mu): mu = 4 gives pi. Energy mu is conserved at every sample.
plateball_cli_test(simulate.period_is_2pi_over_sqrt_mu 0
  --number period ${pi} 1e-12 --number energy 4 1e-9
  -- simulate --mu 4 --lambda 0.5 --theta 1.2 --phi 0.3 --psi 0.9 --t-end 20 --samples 9)
# problems/simulate_example.json: omega = (1, 0, 0) stays constant (v0 = 0, K = omega_h), so the
# contact point moves at speed sqrt(mu) = 1 along -y: drift (0, -2 pi) per period, and at t = T/2
# it is at (0, -pi).
plateball_cli_test(simulate.example_file 0
  --number period ${two_pi} 1e-12 --vector drift_per_period "0,-${two_pi}" 1e-9 --number energy 1 1e-10
  --vector omega "1,0,0" 1e-10
  -- simulate problems/simulate_example.json)
plateball_cli_test(simulate.example_half_period 0 REGEX "\"x\": \\[[-0-9.e]+, -3.14159265358"
  -- simulate problems/simulate_example.json --t-end ${pi} --samples 2)
# Options override the file: mu = 4 doubles |omega| and halves T; the drift per period stays 2 pi.
plateball_cli_test(simulate.options_override_file 0
  --number period ${pi} 1e-12 --vector drift_per_period "0,-${two_pi}" 1e-9 --number energy 4 1e-9
  -- simulate problems/simulate_example.json --mu 4 --samples 3)
# theta = 0 (z vertical), phi = psi = 0: (12)-(18) give u = (-1, 0, 0), v0 = 0, so omega = v0 z - u =
# (1, 0, 0); v0 stays 0 and K = omega_h, so omega is constant and x moves straight: x' = omega x e3
# = (0, -1), drift (0, -2 pi) per period (a special case).
plateball_cli_test(simulate.pole_start_rolls_straight 0
  --vector omega "1,0,0" 1e-9 --vector drift_per_period "0,-${two_pi}" 1e-9
  -- simulate --theta 0 --phi 0 --psi 0 --mu 1 --lambda 2 --samples 4)
plateball_cli_test(simulate.writes_out_file 0 --cat ${CMAKE_CURRENT_BINARY_DIR}/cli_simulate_out.json
  --number period ${two_pi} 1e-12
  -- simulate --samples 2 --out ${CMAKE_CURRENT_BINARY_DIR}/cli_simulate_out.json)

# ---------------------------------------------------------------- roll: numbers
# A segment of length L in direction d is the rotation by L about e3 x d:
# (1.2, 1.6) has L = 2, d = (0.6, 0.8), e3 x d = (-0.8, 0.6, 0): rotation vector (-1.6, 1.2, 0).
plateball_cli_test(roll.segment_is_rotation_about_e3_cross_d 0
  --vector rotation_vector "-1.6,1.2,0" 1e-12 --number angle 2 1e-12 --vector axis "-0.8,0.6,0" 1e-12
  -- roll --segment --points "0,0 1.2,1.6")
# L = 5 > pi about e2: the logarithm reports 2 pi - 5 about -e2.
plateball_cli_test(roll.long_segment_angle_wraps 0
  --vector rotation_vector "0,-1.2831853071795865,0" 1e-12 --number angle 1.2831853071795865 1e-12
  -- roll --segment --points "0,0 5,0")
# Out and back along the same segment: the identity.
plateball_cli_test(roll.there_and_back_is_identity 0 --number angle 0 1e-15
  -- roll --segment --points "0,0 1,0 0,0")
# A spline through collinear points is the straight line: rotation by 3 about e2.
plateball_cli_test(roll.spline_through_collinear_points 0
  --vector rotation_vector "0,3,0" 1e-9 --number angle 3 1e-9
  -- roll --points "0,0 1,0 3,0")
# Samples file along +y, length 2.5: rotation by 2.5 about e3 x e2 = -e1.
plateball_cli_test(roll.samples_file 0 --vector rotation_vector "-2.5,0,0" 1e-9
  -- roll --samples-file tests/data/roll_samples.json)
# A full turn on the circle of radius R = 0.75 (tests/data/roll_circle.json, plan.path): with
# A = Rz(t) B, B' = hat(-(R e1 + e3)) B, so R_total = exp(2 pi hat(-(R e1 + e3))), the rotation by
# 2.5 pi about -(0.6, 0, 0.8), i.e. rotation vector (pi/2) (-0.6, 0, -0.8).
plateball_cli_test(roll.problem_circle_closed_form 0
  --vector rotation_vector "-0.9424777960769379,0,-1.2566370614359172" 1e-9
  --number angle 1.5707963267948966 1e-9 --number length 4.71238898038469 1e-9
  -- roll tests/data/roll_circle.json)
plateball_cli_test(roll.problem_without_plan 3 REGEX "simulate_example.json: plan.path: value \\(missing\\)"
  -- roll problems/simulate_example.json)
# Final orientation R A0 with A0 = rotation by pi/2 about e3 and R = rotation by 2 about e2
# (segment (0,0)-(2,0)): R A0 = [[0, -cos 2, sin 2], [1, 0, 0], [0, sin 2, cos 2]]; its second row
# is printed as [1.0, 0.0, 0.0] up to round-off.
plateball_cli_test(roll.final_orientation 0 REGEX "\"orientation_final\": \\[\\[[-0-9.e]+, 0.41614683654714[0-9]*, 0.90929742682568[0-9]*\\]"
  -- roll --segment --points "0,0 2,0" --orientation "{\"axis_angle\": {\"axis\": [0, 0, 1], \"angle\": 1.5707963267948966}}")

# ---------------------------------------------------------------- bad input: exact exit codes
# 3 = invalid input (message names the field and value), 2 = usage, 4 = computation failed,
# 5 = unreadable or unwritable file.
plateball_cli_test(simulate.negative_mu 3 REGEX "--mu: value -1: must be" -- simulate --mu -1)
plateball_cli_test(simulate.nan_mu 3 REGEX "--mu: value nan" -- simulate --mu nan)
plateball_cli_test(simulate.non_numeric_mu 3 REGEX "plateball simulate: invalid input: command line: --mu: value \"abc\": must be a number" -- simulate --mu abc)
plateball_cli_test(simulate.zero_samples 3 REGEX "--samples: value 0: must be >= 2" -- simulate --samples 0)
plateball_cli_test(simulate.negative_t_end 3 REGEX "--t-end: value -1" -- simulate --t-end -1)
plateball_cli_test(simulate.bad_x0 3 REGEX "--x0: value \"1\": must be two finite numbers" -- simulate --x0 1)
plateball_cli_test(steer.negative_seed 3 REGEX "--seed: value \"-1\"" -- steer --seed -1)
# Deterministic subcommands take no --seed (it would mean nothing: Reach runs DIRECT-L and BOBYQA).
plateball_cli_test(simulate.no_seed 2 REGEX "not expected: --seed" -- simulate --seed 1)
plateball_cli_test(reach.no_seed 2 REGEX "not expected: --seed" -- reach --targets 6,0 --seed 1)
plateball_cli_test(simulate.zero_tolerance 3 REGEX "--atol: value 0: must be in" -- simulate --atol 0)
plateball_cli_test(simulate.non_rotation_orientation 3
  REGEX "--orientation.matrix: value \\[\\[1, 0, 0\\], \\[0, 1, 0\\], \\[0, 0, 2\\]\\]: not a rotation"
  -- simulate --orientation "{\"matrix\": [[1,0,0],[0,1,0],[0,0,2]]}")
plateball_cli_test(simulate.bad_problem_file 3 REGEX "bad_mu.json: initial.mu: value -1: must be > 0"
  -- simulate tests/data/bad_mu.json)
plateball_cli_test(simulate.missing_problem_file 5 REGEX "no_such_problem.json.*cannot open"
  -- simulate tests/data/no_such_problem.json)
plateball_cli_test(simulate.unwritable_out 5 REGEX "out.json: cannot write \\(--out\\): the directory /nonexistent-dir does not exist"
  -- simulate --samples 2 --out /nonexistent-dir/out.json)
plateball_cli_test(simulate.step_limit 4 REGEX "max_steps = 3" -- simulate --max-steps 3)
plateball_cli_test(simulate.unknown_option 2 -- simulate --no-such-option)
plateball_cli_test(roll.one_point 3 REGEX "--points: value \"0,0\": must give at least 2 points" -- roll --points "0,0")
plateball_cli_test(roll.repeated_point 3 REGEX "--points\\[1\\]: value \\[1.0, 2.0\\]: repeats" -- roll --points "1,2 1,2")
plateball_cli_test(roll.no_path 3 REGEX "give exactly one path" -- roll)
plateball_cli_test(roll.two_paths 3 REGEX "value \\(2 given\\): give exactly one path"
  -- roll tests/data/roll_circle.json --points "0,0 1,0")
plateball_cli_test(roll.missing_samples_file 5 -- roll --samples-file tests/data/no_such_samples.json)
plateball_cli_test(roll.bad_samples_file 3 REGEX "bad_mu.json: ball: value" -- roll --samples-file tests/data/bad_mu.json)

# ';' separates points too (registered directly: a CMake list would split the argument).
add_test(NAME cli.roll.semicolon_separated_points
         COMMAND bash ${PROJECT_SOURCE_DIR}/tests/scripts/check_cli.sh 0 --vector rotation_vector "-1.6,1.2,0" 1e-12
                 -- $<TARGET_FILE:plateball_cli> roll --segment --points "0,0;0.6,0.8;1.2,1.6")
set_tests_properties(cli.roll.semicolon_separated_points PROPERTIES LABELS cli TIMEOUT 120)

# The plain binary fails (non-zero exit) on bad input, without the wrapper too.
add_test(NAME cli.simulate.bad_input_fails COMMAND plateball_cli simulate --mu 0)
set_tests_properties(cli.simulate.bad_input_fails PROPERTIES WILL_FAIL TRUE LABELS cli)
