# The one command line: `plateball isoparallel` shares isoparallel_solve's code and the
# problem options, the same option names and exit codes in every tool, "-" for standard input,
# and messages that name the option and the subcommand. Uses plateball_cli_test (cli_tests.cmake).
if(NOT TARGET plateball_cli OR NOT TARGET isoparallel_solve)
  return()
endif()

function(contract_shell_test name regex script)
  add_test(NAME cli.contract.${name} COMMAND bash -o pipefail -c "${script}" WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  set_tests_properties(cli.contract.${name} PROPERTIES TIMEOUT 120 LABELS cli PASS_REGULAR_EXPRESSION "${regex}")
endfunction()
set(pb $<TARGET_FILE:plateball_cli>)
set(iso $<TARGET_FILE:isoparallel_solve>)

# The subcommand solves the built-in Figure 7 problem like isoparallel_solve (golden shortest
# length 9.41277243, problems/figure7.json) and prints the JSON of the contract.
plateball_cli_test(contract.isoparallel_subcommand 0
  REGEX "\"command\": \"isoparallel\".*\"solutions\": \\[[^]]*\"length\": 9\\.41277242"
  -- isoparallel)
plateball_cli_test(contract.isoparallel_threads_and_goal 0
  REGEX "\"goal\": \\[3\\.0, 3\\.0\\].*\"solutions\": \\[[^]]*\"length\": 9\\.41277242"
  -- isoparallel --threads 2 --goal 3,3 --impulses 12)
plateball_cli_test(contract.isoparallel_goal_beyond_limit 3
  REGEX "plateball isoparallel: invalid input: command line: --goal: value \\[100, 0\\]"
  -- isoparallel --goal 100,0)
plateball_cli_test(contract.isoparallel_goal_orientation_named 3
  REGEX "command line: --goal-orientation.matrix: value"
  -- isoparallel --goal-orientation "{\"matrix\": [[1,0,0],[0,2,0],[0,0,1]]}")
plateball_cli_test(contract.isoparallel_threads_range 3 REGEX "--threads: value 0: must be >= 1"
  -- isoparallel --threads 0)
# The same failure, the same exit code and message in both entry points.
foreach(tool plateball_isoparallel isoparallel_solve)
  if(tool STREQUAL "isoparallel_solve")
    set(cmd ${iso})
  else()
    set(cmd "${pb} isoparallel")
  endif()
  contract_shell_test(${tool}_non_numeric "--starts: value \"abc\": must be an integer.*exit 3"
    "${cmd} --starts abc; echo exit $?")
  contract_shell_test(${tool}_impulses_range "--impulses: value 0: must be >= 1.*exit 3"
    "${cmd} --impulses 0; echo exit $?")
endforeach()

# Messages name the option (not the library field) and the subcommand.
plateball_cli_test(contract.lambda_range_names_option 3
  REGEX "plateball simulate: invalid input: command line: --lambda: value 10000: must be in \\[0.001, 1000\\]"
  -- simulate --lambda 1e4)
plateball_cli_test(contract.mu_range_names_option 3 REGEX "command line: --mu: value 10000000000000: must be in"
  -- simulate --mu 1e13)
contract_shell_test(empty_value_names_subcommand
  "plateball simulate: invalid input: command line: --theta: value \"\": must not be empty.*exit 3"
  "${pb} simulate --theta ''; echo exit $?")
plateball_cli_test(contract.plan_impulses_limit_names_option 3
  REGEX "command line: --impulses: value 1000000: must be <= 10000 \\(n x 1 smooth piece"
  -- plan problems/circle.json --n 1000000)
plateball_cli_test(contract.converge_integer_option 3 REGEX "plateball converge: .*--impulses: value \"1.5\": must be an integer"
  -- converge problems/circle.json --impulses 16,1.5)

# "-" reads the problem from standard input.
contract_shell_test(plan_from_stdin "\"file\": \"-\".*\"measured_error\": 0\\.0149028364"
  "${pb} plan - --summary-only < problems/circle.json")
contract_shell_test(isoparallel_solve_from_stdin "shortest length: 9\\.41277243"
  "${iso} - < problems/figure7.json")
contract_shell_test(roll_samples_from_stdin "\"reorientation\""
  "${pb} roll --samples-file - < tests/data/roll_samples.json")
