// Messages <-> engine types: the only place where ROS messages meet the core.
#pragma once

#include <optional>
#include <string>

#include <std_msgs/Header.h>

#include "sap_broadphase/BoxArray.h"
#include "sap_broadphase/PairArray.h"
#include "sap_broadphase/core/box_set.h"
#include "sap_broadphase/core/pair_set.h"

namespace sap_broadphase {

/// Cheap O(1) check of the array lengths of a BoxArray: bounds 6 per box, ids/groups/masks
/// empty or one per box. Returns the reason of a refusal, or nothing when the shape is right.
std::optional<std::string> checkBoxArrayShape(const BoxArray& inMsg);

/// The boxes of a BoxArray whose shape is checked (checkBoxArrayShape), read where they lie:
/// Broadphase::update() takes them without a copy into a BoxSet and checks them itself. Valid
/// while inMsg is.
BoxSpan boxArrayRecords(const BoxArray& inMsg);

/// Copies the boxes of a BoxArray whose shape is checked (checkBoxArrayShape) into outBoxes
/// (replaced; capacity reused) as they are, for the engine to check as it loads them. Empty
/// `ids` number the boxes 0..n-1.
void copyBoxArray(const BoxArray& inMsg, BoxSet& outBoxes);

/// Fills outMsg (replaced) with inPairs as consecutive id pairs, header copied from inHeader.
void pairListToPairArray(const PairList& inPairs, const std_msgs::Header& inHeader,
                         PairArray& outMsg);

/// Fills outMsg (replaced) with the boxes of inBoxes; ids are always written.
void boxSetToBoxArray(const BoxSet& inBoxes, const std_msgs::Header& inHeader, BoxArray& outMsg);

}  // namespace sap_broadphase
