# Optional MPI component of `plateball montecarlo`: with Open MPI found (Debian's
# libopenmpi-dev), `mpirun -np K plateball montecarlo ...` splits the trials over the ranks
# (tools/plateball/montecarlo_ranks.cc). Without it the tool runs its trials on threads. Not in
# sanitizer or fuzz builds: Open MPI's own allocations would be reported as leaks.
option(PLATEBALL_MPI "Build plateball montecarlo with MPI when an MPI implementation is found" ON)
set(PLATEBALL_WITH_MPI OFF)
if(PLATEBALL_MPI AND TARGET plateball_cli AND NOT PLATEBALL_SANITIZE AND NOT PLATEBALL_FUZZ)
  set(MPI_CXX_SKIP_MPICXX ON)  # the C API only, no deprecated C++ bindings
  find_package(MPI COMPONENTS CXX QUIET)
  if(MPI_CXX_FOUND)
    target_link_libraries(plateball_cli PRIVATE MPI::MPI_CXX)
    target_compile_definitions(plateball_cli PRIVATE PLATEBALL_WITH_MPI)
    set(PLATEBALL_WITH_MPI ON)
    message(STATUS "plateball montecarlo: MPI found (${MPI_CXX_LIBRARIES}); mpiexec: ${MPIEXEC_EXECUTABLE}")
  else()
    message(STATUS "plateball montecarlo: MPI not found, trials run on threads only")
  endif()
endif()
