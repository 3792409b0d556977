// The portals of a demo building; see vtkDemoScenePortals.h.
#include "vtkDemoScenePortals.h"

#include "scenevis/Scenes.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

namespace scenevis
{

vtkSmartPointer<vtkPolyData> MakePortalPolyData(const scenes::BuildingScene& building)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkIntArray> a, c;
  a->SetName("RoomA");
  c->SetName("RoomB");
  for (const auto& p : building.portals)
  {
    polys->InsertNextCell(static_cast<vtkIdType>(p.polygon.size()));
    for (const auto& q : p.polygon)
    {
      polys->InsertCellPoint(points->InsertNextPoint(q.x, q.y, q.z));
    }
    a->InsertNextValue(p.roomA);
    c->InsertNextValue(p.roomB);
  }
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(points);
  pd->SetPolys(polys);
  pd->GetCellData()->AddArray(a);
  pd->GetCellData()->AddArray(c);
  return pd;
}

} // namespace scenevis
