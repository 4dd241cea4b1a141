// SPDX-License-Identifier: MIT
// A group as the pair queries see it: rigid set of placed models, moved by one
// placement. What the query layer reads, without the pair tracker around it.
#pragma once

#include "smartcollision/model.h"
#include "smartcollision/placement.h"

namespace sc {

/// A model placed in a group's local frame. `id` is reported back in results.
struct Part {
  const Model* model = nullptr;
  Rigid group_from_model;
  int id = -1;
};

/// A group: rigid set of parts, moved by its placement (its centre of rotation is
/// the placement's r_LC / r_WC). Parts are read, not owned.
struct GroupView {
  const Part* parts = nullptr;
  int part_count = 0;
  Placement placement;
};

/// InvalidArgument, saying why, for a view the pair queries cannot use: a negative
/// part_count, null parts with part_count > 0, or a placement Scene::setGroupPlacement
/// refuses (a centre not finite or beyond 1e100 in magnitude, a quaternion not finite
/// or zero). Any other finite quaternion is accepted and normalised where used.
SC_API Status validate(const GroupView& group);

}  // namespace sc
