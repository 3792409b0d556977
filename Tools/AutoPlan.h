// Auto mode: the facts of a scene that --cull auto and --sort auto decide on (parts, triangles,
// translucency, rooms and portals, what the first camera sees) and the plan made from them: the
// culling mode, the translucency method and the groups drawn as actors, each with its reason.
#ifndef scenevis_tool_AutoPlan_h
#define scenevis_tool_AutoPlan_h

#include "Instances.h"
#include "Options.h"
#include "SceneLoading.h"
#include "vtkScenePlanRule.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <cstddef>
#include <set>
#include <string>
#include <vector>

class vtkRenderer;

namespace scenevis
{
namespace tool
{

/// What auto mode decides on, and what the reports quote as the reason: the library's facts, so
/// that the command line and vtkSceneVisPlanner decide by one rule (vtkScenePlanRule).
using SceneFacts = vtkScenePlanFacts;

/// The distinct values of the one-component cell array @p name (all cells, or @p cells only).
std::set<long long> DistinctValues(
  vtkPolyData* pd, const char* name, const std::vector<vtkIdType>* cells = nullptr);

/// The culling mode to use and why.
struct CullPlan
{
  std::string method;
  std::string reason;
  bool needsActors = false; ///< a prop culler: one actor per part / room
  bool chunked = false;
  double smallPixels = 0.0;
  std::string roomArray = "RoomId"; ///< the cell array the portal culler reads rooms from
  double pvsBudget = 0.0;           ///< --cull pvs: the precompute's budget in seconds (0: none)
  int chunkSize = 0;                ///< chunked: triangles per chunk (0: the mapper's default)
  std::string recordOcclusion; ///< (chunked-)occlusion: the file culls are recorded to ("": none)

  /// The cullers the method runs (Options.h: CullUsesPortals and the others).
  bool Portals() const { return CullUsesPortals(method); }
  bool Pvs() const { return CullUsesPvs(method); }
  bool Occlusion() const { return CullUsesOcclusion(method); }
};

/// The --cull plan applied to a loaded scene: the groups drawn as actors and the sort method.
struct ScenePlan
{
  SceneFacts facts;
  CullPlan cull;
  std::vector<vtkSmartPointer<vtkPolyData>> groups;
  std::string sort;
  std::string sortReason;
  /// --instances: the placed meshes (groups then holds the meshes, one mapper each).
  const InstancedScene* instanced = nullptr;
  /// --instances drawn as one vtkInstancedActor per mesh (culled per placement), not one actor
  /// per placement: culling none, octree or occlusion (VTK's frustum culler sees props, not
  /// placements), sort none, oit or peel:N, and no --instance-actors.
  bool instancedProps = false;
  double inspectMs = 0.0; ///< reading the scene's facts (parts, rooms, translucency, view)
  double splitMs = 0.0;   ///< splitting it into one polydata per part / room
  /// The portals the portal culler reads: the scene's, or those --cull auto generated (then the
  /// scene's polydata holds the generated rooms in its room array).
  vtkSmartPointer<vtkPolyData> portals;
  double generateMs = 0.0; ///< --cull auto: the architectural test and room generation
};

/// The plan for @p scene: its facts (with 100+ parts, also what the first camera sees), the
/// --cull mode (auto: chosen from the facts), the groups drawn as actors and the translucency
/// method for @p sort (auto: chosen with the culling). --cull auto on a scene without rooms and
/// portals that looks architectural (GeneratedRooms.h) generates them: the scene's room array
/// is replaced by the generated rooms and plan.portals holds the generated portals. @p renderer:
/// its camera already set up, for what the first frame sees. With @p releaseSplitScene, a split
/// leaves the scene without its polygons (the caller draws the parts only and lets the scene go;
/// see SplitByKeys). Throws UsageError for a mode the scene cannot take.
ScenePlan PlanScene(const Options& options, const LoadedScene& scene, const std::string& sort,
  vtkRenderer* renderer, bool releaseSplitScene = false);

} // namespace tool
} // namespace scenevis

#endif
