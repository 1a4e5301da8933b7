# Benchmarks: sap_bench (experiments, peers, plots) and sap_microbench (Google
# Benchmark). Peers are optional: each adapter is compiled only when its library is found.
set(SAP_BENCH_DIR ${CMAKE_CURRENT_LIST_DIR})

add_executable(sap_bench
  ${SAP_BENCH_DIR}/sap_bench_main.cpp
  ${SAP_BENCH_DIR}/bench_machine.cpp
  ${SAP_BENCH_DIR}/bench_options.cpp
  ${SAP_BENCH_DIR}/bench_table.cpp
  ${SAP_BENCH_DIR}/bench_plot.cpp
  ${SAP_BENCH_DIR}/bench_progress.cpp
  ${SAP_BENCH_DIR}/bench_output.cpp
  ${SAP_BENCH_DIR}/bench_scenes.cpp
  ${SAP_BENCH_DIR}/engine_runner.cpp
  ${SAP_BENCH_DIR}/bench_paper_runs.cpp
  ${SAP_BENCH_DIR}/pair_diff.cpp
  ${SAP_BENCH_DIR}/exp_fig1_sort.cpp
  ${SAP_BENCH_DIR}/exp_fig23_phases.cpp
  ${SAP_BENCH_DIR}/exp_fig4_stacked.cpp
  ${SAP_BENCH_DIR}/exp_dispersion.cpp
  ${SAP_BENCH_DIR}/exp_fig5_ball.cpp
  ${SAP_BENCH_DIR}/exp_fig6_plane.cpp
  ${SAP_BENCH_DIR}/exp_threads.cpp
  ${SAP_BENCH_DIR}/exp_pareto.cpp
  ${SAP_BENCH_DIR}/exp_peers.cpp
  ${SAP_BENCH_DIR}/exp_memory.cpp
  ${SAP_BENCH_DIR}/exp_skips.cpp
  ${SAP_BENCH_DIR}/exp_coherence.cpp
  ${SAP_BENCH_DIR}/exp_distributed.cpp
  ${SAP_BENCH_DIR}/exp_sizes.cpp
  ${SAP_BENCH_DIR}/exp_busy.cpp
  ${SAP_BENCH_DIR}/peer_runs.cpp
  ${SAP_BENCH_DIR}/exp_query.cpp
  ${SAP_BENCH_DIR}/exp_events.cpp
  ${SAP_BENCH_DIR}/bench_memory.cpp
  ${SAP_BENCH_DIR}/peers/peer_registry.cpp
  ${SAP_BENCH_DIR}/peers/peer_grid.cpp
  ${SAP_BENCH_DIR}/peers/uniform_grid.cpp
)
target_include_directories(sap_bench PRIVATE ${SAP_BENCH_DIR})
target_link_libraries(sap_bench ${PROJECT_NAME}_core_internal OpenMP::OpenMP_CXX)

# ---- Optional peers ----
# Each adapter is its own static library, so a peer's compile flags (CGAL adds
# -frounding-math) stay out of the harness and the engine.
set(SAP_BENCH_PEERS "grid")
function(sap_bench_add_peer inName inSource inDefine)
  add_library(sap_bench_peer_${inName} STATIC ${SAP_BENCH_DIR}/peers/${inSource})
  target_include_directories(sap_bench_peer_${inName} PRIVATE ${SAP_BENCH_DIR})
  target_link_libraries(sap_bench_peer_${inName} PUBLIC ${PROJECT_NAME}_core_internal ${ARGN})
  target_compile_definitions(sap_bench PRIVATE ${inDefine})
  target_link_libraries(sap_bench sap_bench_peer_${inName})
  set(SAP_BENCH_PEERS "${SAP_BENCH_PEERS};${inName}" PARENT_SCOPE)
endfunction()

find_package(CGAL QUIET)
if(CGAL_FOUND AND TARGET CGAL::CGAL)
  sap_bench_add_peer(cgal peer_cgal.cpp SAP_BENCH_WITH_CGAL CGAL::CGAL)
  # CGAL's Parallel_tag version needs TBB (libtbb-dev); without it only the sequential one.
  find_package(TBB QUIET)
  include(CGAL_TBB_support OPTIONAL)
  if(TARGET CGAL::TBB_support)
    target_link_libraries(sap_bench_peer_cgal PUBLIC CGAL::TBB_support)
    target_compile_definitions(sap_bench_peer_cgal PRIVATE SAP_BENCH_CGAL_PARALLEL)
    set(SAP_BENCH_PEERS "${SAP_BENCH_PEERS};cgal_tbb")
  endif()
endif()

# Debian ships Bullet in float and double builds; the double one (-float64) compares the
# same float64 boxes the engine sees.
find_path(SAP_BULLET_INCLUDE_DIR btBulletCollisionCommon.h PATH_SUFFIXES bullet)
find_library(SAP_BULLET_COLLISION BulletCollision-float64)
find_library(SAP_BULLET_LINEARMATH LinearMath-float64)
if(SAP_BULLET_INCLUDE_DIR AND SAP_BULLET_COLLISION AND SAP_BULLET_LINEARMATH)
  sap_bench_add_peer(bullet peer_bullet.cpp SAP_BENCH_WITH_BULLET
    ${SAP_BULLET_COLLISION} ${SAP_BULLET_LINEARMATH})
  target_compile_definitions(sap_bench_peer_bullet PRIVATE BT_USE_DOUBLE_PRECISION)
  target_include_directories(sap_bench_peer_bullet SYSTEM PRIVATE ${SAP_BULLET_INCLUDE_DIR})
endif()

# FCL's package config needs the Eigen3::Eigen target.
find_package(Eigen3 QUIET NO_MODULE)
if(TARGET Eigen3::Eigen)
  find_package(fcl QUIET)
endif()
if(fcl_FOUND AND TARGET fcl)
  sap_bench_add_peer(fcl peer_fcl.cpp SAP_BENCH_WITH_FCL fcl)
endif()
# PhysX: only from a source checkout named with -DSAP_PHYSX_DIR (bench/physx.cmake).
include(${SAP_BENCH_DIR}/physx.cmake)
message(STATUS "sap_bench peers: ${SAP_BENCH_PEERS}")

# ---- Google Benchmark microbenchmarks ----
find_package(benchmark QUIET)
if(benchmark_FOUND)
  add_executable(sap_microbench
    ${SAP_BENCH_DIR}/micro/micro_succ_tree.cpp
    ${SAP_BENCH_DIR}/micro/micro_radix_sort.cpp
    ${SAP_BENCH_DIR}/micro/micro_phases.cpp
    ${SAP_BENCH_DIR}/micro/micro_static_index.cpp
    ${SAP_BENCH_DIR}/micro/micro_skin.cpp
    ${SAP_BENCH_DIR}/micro/micro_history.cpp
  )
  target_link_libraries(sap_microbench ${PROJECT_NAME}_core_internal benchmark::benchmark)
else()
  message(STATUS "sap_microbench: Google Benchmark not found, skipped")
endif()

# ---- End to end through ROS; only with the ROS layer (catkin build) ----
if(TARGET ${PROJECT_NAME}_ros)
  include(${SAP_BENCH_DIR}/ros_latency.cmake)
endif()

# The benchmark tools are installed beside the package's other executables.
foreach(sap_bench_tool sap_bench sap_microbench)
  if(TARGET ${sap_bench_tool})
    install(TARGETS ${sap_bench_tool} RUNTIME DESTINATION ${SAP_BIN_DESTINATION})
  endif()
endforeach()
