// The engine as the ROS layer sees it.
//
// The core's per-frame statistics struct and the generated FrameStats message share the name
// sap_broadphase::FrameStats. Until the core renames its struct, the ROS layer includes the
// engine through this header, which names the core struct EngineFrameStats in ROS translation
// units (only a name: member functions do not mangle their return types, so it links as is).
#pragma once

#define FrameStats EngineFrameStats
#include "sap_broadphase/core/broadphase.h"
#undef FrameStats
