# NVIDIA PhysX 5's CPU broad phases (ABP, PABP, MBP) as a peer of sap_bench, compiled from a
# PhysX source checkout the user names with -DSAP_PHYSX_DIR=/path/to/PhysX (the repository
# root, or its physx/ folder). PhysX is BSD-3 and is never copied into this repository.
#
# PhysX's own build fetches its tool chain with packman; instead only what the broad phase needs
# is compiled here: the foundation, the low-level broad phase (lowlevelaabb), the radix sort of
# common/, the task manager and the default CPU dispatcher of the extensions, with the defines
# and flags of PhysX's Linux release configuration (source/compiler/cmake/linux/CMakeLists.txt).
# Included by bench.cmake after sap_bench_add_peer is defined.
set(SAP_PHYSX_DIR "" CACHE PATH "PhysX source checkout for the PhysX peer of sap_bench (off when empty)")
if(NOT SAP_PHYSX_DIR)
  return()
endif()

set(sap_physx_root "${SAP_PHYSX_DIR}")
if(EXISTS "${SAP_PHYSX_DIR}/physx/include/PxBroadPhase.h")
  set(sap_physx_root "${SAP_PHYSX_DIR}/physx")
endif()
if(NOT EXISTS "${sap_physx_root}/include/PxBroadPhase.h" OR
   NOT EXISTS "${sap_physx_root}/source/lowlevelaabb/src/BpBroadPhaseABP.cpp")
  message(FATAL_ERROR "SAP_PHYSX_DIR=${SAP_PHYSX_DIR}: no PhysX 5 source tree there "
                      "(expected physx/include/PxBroadPhase.h and physx/source/lowlevelaabb)")
endif()
set(sap_physx_src "${sap_physx_root}/source")

file(GLOB sap_physx_sources
  "${sap_physx_src}/foundation/*.cpp"
  "${sap_physx_src}/foundation/unix/*.cpp"
  "${sap_physx_src}/lowlevelaabb/src/BpBroadPhase*.cpp"
  "${sap_physx_src}/lowlevelaabb/src/BpFiltering.cpp"
)
list(APPEND sap_physx_sources
  "${sap_physx_src}/common/src/CmRadixSort.cpp"
  "${sap_physx_src}/task/src/TaskManager.cpp"
  "${sap_physx_src}/physxextensions/src/ExtDefaultCpuDispatcher.cpp"
  "${sap_physx_src}/physxextensions/src/ExtCpuWorkerThread.cpp"
)

add_library(sap_physx_broadphase STATIC ${sap_physx_sources})
# PUBLIC: the peer's adapter includes the broad phase's headers with the same definitions.
target_include_directories(sap_physx_broadphase SYSTEM PUBLIC
  "${sap_physx_root}/include"
  "${sap_physx_src}/common/include"
  "${sap_physx_src}/common/src"
  "${sap_physx_src}/geomutils/include"
  "${sap_physx_src}/geomutils/src"
  "${sap_physx_src}/lowlevel/api/include"
  "${sap_physx_src}/lowlevel/common/include/utils"
  "${sap_physx_src}/lowlevel/common/include/pipeline"
  "${sap_physx_src}/lowlevelaabb/include"
  "${sap_physx_src}/lowlevelaabb/src"
  "${sap_physx_src}/physxextensions/src"
)
target_compile_definitions(sap_physx_broadphase PUBLIC
  PX_PHYSX_STATIC_LIB DISABLE_CUDA_PHYSX PX_SUPPORT_GPU_PHYSX=0 PX_SUPPORT_PVD=0
  PX_SUPPORT_OMNI_PVD=0 PX_PUBLIC_RELEASE=1 PX_NVTX=0 NDEBUG)
# PhysX's flags for its own sources; its warnings are its own (-w).
target_compile_options(sap_physx_broadphase PRIVATE
  -fno-rtti -fno-exceptions -fno-strict-aliasing -ffunction-sections -fdata-sections -w -O3)
set_target_properties(sap_physx_broadphase PROPERTIES POSITION_INDEPENDENT_CODE ON)
find_package(Threads REQUIRED)
target_link_libraries(sap_physx_broadphase PUBLIC Threads::Threads ${CMAKE_DL_LIBS})

sap_bench_add_peer(physx peer_physx.cpp SAP_BENCH_WITH_PHYSX sap_physx_broadphase)
