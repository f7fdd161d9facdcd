# Command-line tests of the "figures" and "one command line" items: figure axes, legends,
# start/goal markers and --figure-size; streamed CSV samples; progress and --quiet; physical
# units; the man page and the bash completion. (Named ux_* so that cli_tests.cmake, which
# defines plateball_cli_test, is read first.)
if(NOT TARGET plateball_cli)
  return()
endif()
set(ux ${CMAKE_CURRENT_BINARY_DIR})

# ---------------------------------------------------------------- figures
plateball_cli_test(figure.plan_axes_and_legend 0
  REGEX "x \\(ball radii\\).*y \\(ball radii\\).*start \\(arrow: direction of motion\\).*goal \\(arrow: direction of arrival\\).*planned path"
  --cat ${ux}/ux_plan.svg -- plan problems/circle.json --n 16 --summary-only --svg ${ux}/ux_plan.svg)
plateball_cli_test(figure.converge_a_priori_bound 0 REGEX "a-priori bound, Theorem 2.6.*fit: slope"
  --cat ${ux}/ux_converge.svg -- converge problems/circle.json --n 16,32 --svg ${ux}/ux_converge.svg)
plateball_cli_test(figure.reach_labels_delta_psi_and_t 0 REGEX "1: \\(6, 0\\) reached: Δψ = [-0-9.]+, t = [0-9.]+"
  --cat ${ux}/ux_reach.svg -- reach problems/figure8_reach.json --svg ${ux}/ux_reach.svg)
plateball_cli_test(figure.size 0 REGEX "<svg[^>]* width=\"800\" height=\"500\""
  --cat ${ux}/ux_size.svg -- plan problems/circle.json --n 8 --summary-only --figure-size 800x500 --svg ${ux}/ux_size.svg)
plateball_cli_test(figure.size_invalid 3 REGEX "--figure-size: value \"10x10\": must be WIDTHxHEIGHT"
  -- plan problems/circle.json --figure-size 10x10 --svg ${ux}/ux_bad.svg)

# ---------------------------------------------------------------- streamed samples (CSV)
# mu = 4: period pi; at t = pi/2 and pi the energy column is mu = 4 (conserved).
plateball_cli_test(simulate.csv 0
  REGEX "t,angles.theta,angles.phi,angles.psi,z.0,z.1,z.2,x.0,x.1,orientation.0.0[^\n]*,energy\n0,[^\n]*,4\n1.5707963267948966,[^\n]*,(4|3.999999999999999[0-9]*)\n3.141592653589793,[^\n]*,(4|3.999999999999999[0-9]*)\n"
  -- simulate --mu 4 --t-end 3.141592653589793 --samples 3 --csv -)

# ---------------------------------------------------------------- progress, --quiet
plateball_cli_test(progress.final_line 0 REGEX "plateball converge: done \\(48 of 48\\) in"
  -- converge problems/circle.json --n 16,32 --format csv --progress)
plateball_cli_test(progress.quiet_excludes_progress 2 REGEX "excludes"
  -- converge problems/circle.json --quiet --progress)
plateball_cli_test(reach.quiet 0 -- reach problems/figure8_reach.json --targets "6,0" --quiet)
# The JSON's "report" says "Reach: solved" too; the summary line on stderr starts a line.
set_tests_properties(cli.reach.quiet PROPERTIES FAIL_REGULAR_EXPRESSION "\nReach: solved")

# ---------------------------------------------------------------- physical units
# E = mu (I1 + (M_ball + 4 M_plate) r^2) / 2 = 4 (1.6e-5 + 0.3 * 4e-4) / 2 = 2.72e-4 J; lengths
# scale by r = 0.02 m, time by 1 s: t_end 3 s, the target (6, 0) radii is (0.12, 0) m.
plateball_cli_test(units.simulate 0 REGEX "\"scales\": \\{[^}]*\"length_m\": 0.02,[^}]*\"time_s\": 1.0"
  --number kinetic_energy_J 2.72e-4 1e-18 --number t_end 3 0
  -- simulate problems/physical_units.json)
plateball_cli_test(units.reach 0 REGEX "\"target\": \\[6.0, 0.0\\],.*\"si\": {\n *\"target\": \\[0.12, 0.0\\]"
  -- reach problems/physical_units.json)
plateball_cli_test(units.invalid_radius 3 REGEX "ball.physical.radius: value -0.02"
  -- simulate tests/data/physical_bad_radius.json)

# ---------------------------------------------------------------- man page, completion
if(TARGET plateball_man)
  add_test(NAME man.plateball_page
           COMMAND bash -c "grep -q '^\\.TH PLATEBALL' \"$1\" && grep -c '^\\.SH \"SUBCOMMAND: ' \"$1\""
                   bash ${PROJECT_BINARY_DIR}/man/plateball.1)
  set_tests_properties(man.plateball_page PROPERTIES PASS_REGULAR_EXPRESSION "^[7-9]|^[1-9][0-9]" LABELS cli)
endif()
add_test(NAME completion.lists_subcommands
         COMMAND bash -c "source \"$1\"; COMP_WORDS=(\"$2\" ''); COMP_CWORD=1; _plateball; echo \"\${COMPREPLY[*]}\"; COMP_WORDS=(\"$2\" simulate --c); COMP_CWORD=2; _plateball; echo \"\${COMPREPLY[*]}\""
                 bash ${PROJECT_SOURCE_DIR}/tools/completion/plateball.bash $<TARGET_FILE:plateball_cli>)
set_tests_properties(completion.lists_subcommands PROPERTIES
  PASS_REGULAR_EXPRESSION "converge identify isoparallel join montecarlo plan reach( rig)? roll simulate steer( view)?\n--csv" LABELS cli)
