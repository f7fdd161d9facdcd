# The actuator's records in the JSON of plan, steer and isoparallel_solve (tools/common/actuator_json.h,
# docs/rig.md): schema-valid, J balanced against the momenta of ball and plate recomputed in Python from
# the reported delta omega, axis and masses, and null with the reason for a lambda-only problem.
if(TARGET plateball_cli AND TARGET isoparallel_solve)
  add_test(NAME cli.actuator.outputs
           COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tests/scripts/actuator_outputs.py
                   --plateball $<TARGET_FILE:plateball_cli> --isoparallel-solve $<TARGET_FILE:isoparallel_solve>
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  set_tests_properties(cli.actuator.outputs PROPERTIES TIMEOUT 120 LABELS "cli;schemas"
                       PASS_REGULAR_EXPRESSION "actuator records checked: [1-9][0-9]* balanced, [1-9][0-9]* null"
                       FAIL_REGULAR_EXPRESSION "FAIL: ")
endif()

# Too little friction for a pulse's force: exit 3 naming the option and the first impulse that would
# slip. The 16-impulse circle's 10 ms pulses need mu_s 0.5476 at the first impulse, then 0.109 to 0.113: with 0.5 only steps[0] slips.
if(COMMAND plateball_cli_test)
  plateball_cli_test(plan.pulse_would_slip 3
    REGEX "command line: --static-friction: value 0.5: impulse steps\\[0\\] would slip: its pulse of 0.01 s needs mu_s >= 0.5475"
    -- plan problems/circle_physical.json --impulses 16 --pulse-duration 0.01 --static-friction 0.5)
  plateball_cli_test(plan.pulse_would_spin 3
    REGEX "command line: --torsional-friction: value 1e-04: impulse steps\\[0\\] would spin: its pulse of 0.01 s needs ell >= 0.000172"
    -- plan problems/circle_physical.json --impulses 16 --pulse-duration 0.01 --torsional-friction 1e-4)
  # Pulses longer than a flight would overlap: the 16-impulse circle's first flight is 0.772 s.
  plateball_cli_test(plan.pulse_longer_than_flight 3
    REGEX "command line: --pulse-duration: value 1: longer than the flight of 0.772[0-9]* s after impulse steps\\[0\\]: its pulse would overlap the next one's"
    -- plan problems/circle_physical.json --impulses 16 --pulse-duration 1)
  plateball_cli_test(steer.friction_needs_pulse 3 REGEX "command line: --static-friction: value 0.6: needs --pulse-duration"
    -- steer problems/figure7_exact.json --static-friction 0.6)
  plateball_cli_test(plan.pulse_error_excludes_duration 2 REGEX "--pulse-error excludes --pulse-duration"
    -- plan problems/circle.json --pulse-error 1e-3 --pulse-duration 0.1)
endif()
