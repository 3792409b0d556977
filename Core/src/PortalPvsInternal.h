#pragma once
// Shared by the PVS methods (PortalPvs.cpp, PortalPvsFlow.cpp); not installed.
#include "scenevis/PortalPvs.h"

#include <cstdint>
#include <vector>

namespace scenevis
{
namespace portals
{

/// Which side of portal @p p's plane its node B is on: +1, -1, or 0 when it cannot be told
/// (non-planar, or the inside tests of its rooms disagree or say nothing).
int portalOrientation(const PortalGraph& g, const GraphPortal& p);

/// Marks in @p seen (size nodeCount()) every node reachable from @p source through portals.
void reachableNodes(const PortalGraph& g, std::int32_t source, std::vector<char>& seen);

/// The PortalFlow and MightSee methods (PortalPvs.h).
PortalPvs computePortalFlow(const PortalGraph& g, const PvsOptions& options, PvsStats& stats);

} // namespace portals
} // namespace scenevis
