// The table of every resource kind (illum/resources/kinds.cpp): one row per kind, each a spec's
// row() (illum/framework/resources.h: ResourceKind).
#pragma once
#include <vector>

#include "illum/framework/resources.h"

namespace vgi {

const std::vector<const ResourceKind*>& resourceKinds();

}  // namespace vgi
