# `plateball montecarlo`: byte-identical output across thread counts and, in a build
# with MPI, across 1, 2 and 3 ranks (tests/scripts/montecarlo_ranks.sh); bad options are exit 3
# naming the option and the value.
if(NOT TARGET plateball_cli)
  return()
endif()
if(PLATEBALL_WITH_MPI)
  set(montecarlo_mpiexec ${MPIEXEC_EXECUTABLE})
else()
  set(montecarlo_mpiexec "")
endif()
add_test(NAME cli.montecarlo.identical_across_threads_and_ranks
         COMMAND bash ${PROJECT_SOURCE_DIR}/tests/scripts/montecarlo_ranks.sh $<TARGET_FILE:plateball_cli> ${montecarlo_mpiexec}
         WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
set_tests_properties(cli.montecarlo.identical_across_threads_and_ranks PROPERTIES TIMEOUT 120 LABELS cli)

plateball_cli_test(montecarlo.help 0 REGEX "--trials.*--strategy.*--noise" -- montecarlo --help)
plateball_cli_test(montecarlo.bad_trials 3 REGEX "--trials: value 0" -- montecarlo problems/circle.json --trials 0)
plateball_cli_test(montecarlo.too_many_trials 3 REGEX "--trials: value 2000000"
  -- montecarlo problems/circle.json --trials 2000000)
plateball_cli_test(montecarlo.bad_strategy 3 REGEX "--strategy: value 'closed_loop': unknown strategy"
  -- montecarlo problems/circle.json --strategy closed_loop)
plateball_cli_test(montecarlo.noise_out_of_range 3 REGEX "command line: --noise timing: value 0.5: must be a number in \\[0, 0.1\\]"
  -- montecarlo problems/circle.json --noise timing=0.5)
plateball_cli_test(montecarlo.noise_not_a_number 3 REGEX "command line: --noise impulse_angle: value 'x'"
  -- montecarlo problems/circle.json --noise impulse_angle=x)
plateball_cli_test(montecarlo.noise_unknown 3 REGEX "--noise: value 'spin': unknown error model"
  -- montecarlo problems/circle.json --noise spin=1)
plateball_cli_test(montecarlo.bad_window 3 REGEX "--exact-window: value 2"
  -- montecarlo problems/circle.json --exact-window 2)
plateball_cli_test(montecarlo.bad_miss_tolerance 3 REGEX "--miss-tolerance: value -1"
  -- montecarlo problems/circle.json --miss-tolerance -1)
plateball_cli_test(montecarlo.sweep_chart_needs_sweep 3 REGEX "--svg-sweep: value x.svg: needs --sweep-n"
  -- montecarlo problems/circle.json --svg-sweep x.svg)
plateball_cli_test(montecarlo.no_plan_section 3 REGEX "plan"
  -- montecarlo problems/simulate_example.json)
# Zero noise: every trial is the plan (the circle's n = 64 error 0.0149 rad, Theorem 2.6).
plateball_cli_test(montecarlo.zero_noise_is_the_plan 0 REGEX "\"orientation_error\": 0.01490297432"
  -- montecarlo problems/circle.json --trials 2 --noise none --strategy feedback --quiet)
# Every feedback trial loses the ball under this noise: the cell has no distribution (null, "no
# trial completed"), never zeros, and the run says so.
set(montecarlo_hard_noise "impulse_magnitude=0.5,impulse_angle=0.5,energy_loss=0.5,timing=0.1,lambda=0.1,observation=0.1")
plateball_cli_test(montecarlo.every_trial_lost_has_no_distribution 0
  REGEX "feedback: no trial completed.*\"completed\": 0,[^}]*\"position_error\": null,[^}]*\"orientation_error\": null,[^}]*\"note\": \"no trial completed\""
  -- montecarlo problems/circle.json --trials 20 --strategy open_loop,feedback --noise ${montecarlo_hard_noise} --quiet)
# A sweep whose feedback cell at n = 64 has no completed trial: that row is missing (null medians)
# and left out of the fit, whose slope is then the two-point slope of n = 16 and 32.
plateball_cli_test(montecarlo.sweep_row_without_data_is_missing 0
  REGEX "\"n\": 64,[^}]*\"median_orientation_error\": null,[^}]*\"missing\": \"no trial completed: left out of slope and local_slopes\"[^]]*\\],[^\"]*\"slope\": -1.99[0-9]*,[^\"]*\"local_slopes\": \\[[^]]*null"
  -- montecarlo problems/circle.json --trials 3 --impulses 16 --sweep-n 32,64 --strategy open_loop,feedback
     --noise ${montecarlo_hard_noise} --quiet)
# -q and --progress like every subcommand: --progress ends with the final line of the trials done.
plateball_cli_test(montecarlo.progress_final_line 0 REGEX "plateball montecarlo \\(trials\\): done \\(4 of 4\\)"
  -- montecarlo problems/circle.json --trials 2 --noise none --progress)
plateball_cli_test(montecarlo.quiet_short_option 0 REGEX "\"command\": \"montecarlo\""
  -- montecarlo problems/circle.json --trials 2 --noise none -q)
# The study's work is bounded up front (README, Limits): 1000 sweep values near 10^4 are refused
# before any of their plans is made, naming the option.
set(montecarlo_many_n 9000)
foreach(n RANGE 9001 9999)
  string(APPEND montecarlo_many_n ",${n}")
endforeach()
plateball_cli_test(montecarlo.sweep_work_is_bounded 3 REGEX "--trials: value 10: the study would execute about 189991280 impulses"
  -- montecarlo problems/circle.json --trials 10 -q --sweep-n ${montecarlo_many_n})
# Under MPI standard input reaches rank 0 only: `montecarlo -` is refused once, clearly (exit 3).
if(PLATEBALL_WITH_MPI)
  add_test(NAME cli.montecarlo.stdin_under_mpi_is_refused
           COMMAND bash -c "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 ${MPIEXEC_EXECUTABLE} --oversubscribe -np 2 $<TARGET_FILE:plateball_cli> montecarlo - --trials 2 -q < problems/circle.json 2>&1; echo exit=$?"
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  set_tests_properties(cli.montecarlo.stdin_under_mpi_is_refused PROPERTIES TIMEOUT 60 LABELS cli
    PASS_REGULAR_EXPRESSION "PROBLEM.json: value -: standard input reaches rank 0 only: under MPI \\(2 ranks\\).*exit=3"
    FAIL_REGULAR_EXPRESSION "malformed")
endif()

# Under an MPI starter every subcommand but montecarlo runs on rank 0 alone: its document is
# printed once (the rank is read from the starter's environment, so this holds in any build).
if(MPIEXEC_EXECUTABLE)
  add_test(NAME cli.mpi.other_subcommands_print_once
           COMMAND bash -c "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 ${MPIEXEC_EXECUTABLE} --oversubscribe -np 2 $<TARGET_FILE:plateball_cli> simulate problems/figure7.json --samples 3 | grep -c '\"command\": \"simulate\"'"
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  set_tests_properties(cli.mpi.other_subcommands_print_once PROPERTIES TIMEOUT 60 LABELS cli
                       PASS_REGULAR_EXPRESSION "^1\n$")
endif()

# With a rig section the nominal plan is `plan`'s (PlanImpulsesOnRig): the same rig record, segments,
# total time and measured error as `plan`'s output; the view re-runs that plan; a plan that cannot
# meet the limits runs no trial (exit 4) unless --rig-check-only; slack limits change nothing
# (tests/scripts/montecarlo_rig_cli.py; the view's checks where `view` is built, web/CMakeLists.txt).
set(montecarlo_rig_view no-view)
if(EXISTS ${PROJECT_SOURCE_DIR}/web/node_modules/three/build/three.module.min.js)
  set(montecarlo_rig_view with-view)
endif()
add_test(NAME cli.montecarlo.rig_nominal_is_plans
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tests/scripts/montecarlo_rig_cli.py $<TARGET_FILE:plateball_cli>
                 ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/montecarlo_rig_cli ${montecarlo_rig_view})
set_tests_properties(cli.montecarlo.rig_nominal_is_plans PROPERTIES TIMEOUT 120 LABELS cli
                     PASS_REGULAR_EXPRESSION "[1-9][0-9]* passed, 0 failed" FAIL_REGULAR_EXPRESSION "FAIL: ")
