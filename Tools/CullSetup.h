// The --cull modes installed on a renderer whose actors exist: each mode's culler wrapped so that
// it is timed, re-uses the visible set while the view does not change, and reports what it kept
// (props, triangles, the culler's own statistics as JSON).
#ifndef scenevis_tool_CullSetup_h
#define scenevis_tool_CullSetup_h

#include "AutoPlan.h"
#include "MethodPipeline.h"
#include "vtkOctreeCuller.h"
#include "vtkPortalCuller.h"

#include <vtkSmartPointer.h>

#include <ostream>
#include <unordered_map>
#include <vector>

class vtkPolyData;
class vtkProp;
class vtkRenderer;

namespace scenevis
{
namespace tool
{

class CullStage;

/// A --cull mode installed on a renderer whose pipeline (actors) exists.
class CullSetup
{
public:
  CullSetup(const CullPlan& plan, const MethodPipeline& pipeline, vtkRenderer* renderer,
    vtkPolyData* scene, vtkPolyData* portals, bool showProgress);

  /// After a render: props drawn, input triangles of what was drawn, cull milliseconds, and
  /// whether the visible set was re-used.
  vtkIdType PropsDrawn() const;
  vtkIdType TrianglesDrawn() const;
  vtkIdType TrianglesTotal() const { return this->TotalTriangles; }
  double CullMs() const;
  bool Reused() const;
  const std::vector<vtkProp*>* Visible() const;
  double SetupMs() const { return this->PvsMs; }

  /// JSON members (with a leading comma) of the mode's own statistics (of its last real cull).
  void Describe(std::ostream& json) const;

private:
  CullPlan Plan;
  const MethodPipeline& Pipeline;
  vtkSmartPointer<CullStage> Stage;
  vtkSmartPointer<vtkOctreeCuller> Octree;
  vtkSmartPointer<vtkPortalCuller> Portal;
  std::unordered_map<vtkProp*, vtkIdType> TrianglesOf;
  vtkIdType TotalTriangles = 0;
  double PvsMs = 0.0;
};

} // namespace tool
} // namespace scenevis

#endif
