// Specification: every demo scene comes out as polydata with one PartId and one RGBA colour per
// polygon, matching the core generator; names resolve; bad sizes give an error, not a crash.
#include "vtkDemoSceneSource.h"

#include "scenevis/testing/Expect.h"

#include "vtkCellData.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include <cstdlib>
#include <iostream>

int TestDemoSceneSource(int, char*[])
{
  vtkNew<vtkDemoSceneSource> source;
  for (const char* name : { "spheres", "cyclic-quads", "triangles", "cad", "building" })
  {
    SCENEVIS_EXPECT(source->SetSceneByName(name));
    source->SetTriangleCount(10000);
    source->SetPartCount(50);
    source->Update();
    vtkPolyData* pd = source->GetOutput();
    const vtkIdType cells = pd->GetNumberOfPolys();
    SCENEVIS_EXPECT(cells > 0);
    auto* parts = vtkIdTypeArray::SafeDownCast(pd->GetCellData()->GetArray("PartId"));
    auto* colors = vtkUnsignedCharArray::SafeDownCast(pd->GetCellData()->GetScalars());
    SCENEVIS_EXPECT(parts && parts->GetNumberOfTuples() == cells);
    SCENEVIS_EXPECT(
      colors && colors->GetNumberOfComponents() == 4 && colors->GetNumberOfTuples() == cells);
    auto* partColors =
      vtkUnsignedCharArray::SafeDownCast(pd->GetFieldData()->GetArray("PartColors"));
    SCENEVIS_EXPECT(partColors != nullptr);
    if (parts && colors && partColors)
    {
      // The per-cell colour is the colour of the cell's part.
      for (vtkIdType c = 0; c < cells; c += 97)
      {
        const vtkIdType p = parts->GetValue(c);
        for (int k = 0; k < 4; ++k)
        {
          SCENEVIS_EXPECT(colors->GetTypedComponent(c, k) == partColors->GetTypedComponent(p, k));
        }
      }
    }
    std::cout << name << ": " << cells << " polygons, " << pd->GetNumberOfPoints() << " points\n";
  }
  // The sphere grid is the 64-sphere scene and has about the requested triangle count.
  source->SetScene(vtkDemoSceneSource::SCENE_SPHERE_GRID);
  source->SetTriangleCount(100000);
  source->Update();
  const vtkIdType triangles = source->GetOutput()->GetNumberOfPolys();
  SCENEVIS_EXPECT(triangles > 98000 && triangles < 102000);
  SCENEVIS_EXPECT(
    source->GetOutput()->GetFieldData()->GetAbstractArray("PartNames")->GetNumberOfTuples() == 64);
  SCENEVIS_EXPECT(!source->SetSceneByName("no-such-scene"));
  return scenevis::testing::ExpectFailures() == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
