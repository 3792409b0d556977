// The commands of scenevis, one file each: CommandRender.cxx, CommandSort.cxx,
// CommandCull.cxx, CommandPortals.cxx and CommandBench.cxx. Each returns the exit code; errors are
// thrown (UsageError: exit 2, anything else: exit 1).
#ifndef scenevis_tool_Commands_h
#define scenevis_tool_Commands_h

#include "Options.h"

namespace scenevis
{
namespace tool
{

/// `scenevis render`: the scene drawn offscreen with the --sort and --cull methods (auto: planned
/// from the scene's facts), frames written as PNG, the report printed (and written: --report).
int RunRender(const Options& options);

/// `scenevis sort`: the polydata in BSP order for the camera, or for each camera of --cameras
/// (OUT-0.vtp, OUT-1.vtp, ...: the tree is built once, each camera only re-orders it).
int RunSort(const Options& options);

/// `scenevis cull`: what a mode keeps for one camera (or each camera of --cameras: an array), as
/// JSON on stdout. The visible set is that of a real (offscreen) render, so it is exactly what
/// `render` would draw.
int RunCull(const Options& options);

/// `scenevis portals`: rooms and portals found from the scene's geometry, written as OUT.vtp (the
/// scene with a room cell array) and OUT-portals.vtp (RoomA, RoomB); what was found as JSON on
/// stdout.
int RunPortals(const Options& options);

/// `scenevis bench`: accuracy against time of every translucency method on each scene, as a CSV
/// table and a plot in --out-dir.
int RunBench(const Options& options);

} // namespace tool
} // namespace scenevis

#endif
