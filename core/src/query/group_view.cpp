// SPDX-License-Identifier: MIT
// validate(GroupView): what the pair queries need of a group, checked in O(1) so that
// PairTracker can afford it on every update.
#include "geometry/placement_check.h"
#include "smartcollision/group.h"

namespace sc {

Status validate(const GroupView& group) {
  if (group.part_count < 0)
    return Status(ErrorCode::InvalidArgument, "GroupView::part_count is negative");
  if (group.part_count > 0 && group.parts == nullptr)
    return Status(ErrorCode::InvalidArgument, "GroupView::parts is null but part_count > 0");
  return detail::checkPlacement(group.placement);
}

}  // namespace sc
