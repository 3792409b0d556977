// Specification: every demo scene comes out as polydata with one PartId and one RGBA colour per
// polygon, matching the core generator; names resolve; bad sizes give an error, not a crash.
#include "vtkDemoSceneSource.h"

#include "vtkCellData.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include <cstdlib>
#include <iostream>

namespace
{
int failures = 0;
#define EXPECT(cond)                                                                               \
  do                                                                                               \
  {                                                                                                \
    if (!(cond))                                                                                   \
    {                                                                                              \
      std::cerr << __FILE__ << ":" << __LINE__ << ": expected " #cond << std::endl;                \
      ++failures;                                                                                  \
    }                                                                                              \
  } while (false)
} // namespace

int TestDemoSceneSource(int, char*[])
{
  vtkNew<vtkDemoSceneSource> source;
  for (const char* name : { "spheres", "cyclic-quads", "triangles", "cad", "building" })
  {
    EXPECT(source->SetSceneByName(name));
    source->SetTriangleCount(10000);
    source->SetPartCount(50);
    source->Update();
    vtkPolyData* pd = source->GetOutput();
    const vtkIdType cells = pd->GetNumberOfPolys();
    EXPECT(cells > 0);
    auto* parts = vtkIdTypeArray::SafeDownCast(pd->GetCellData()->GetArray("PartId"));
    auto* colors = vtkUnsignedCharArray::SafeDownCast(pd->GetCellData()->GetScalars());
    EXPECT(parts && parts->GetNumberOfTuples() == cells);
    EXPECT(colors && colors->GetNumberOfComponents() == 4 && colors->GetNumberOfTuples() == cells);
    auto* partColors =
      vtkUnsignedCharArray::SafeDownCast(pd->GetFieldData()->GetArray("PartColors"));
    EXPECT(partColors != nullptr);
    if (parts && colors && partColors)
    {
      // The per-cell colour is the colour of the cell's part.
      for (vtkIdType c = 0; c < cells; c += 97)
      {
        const vtkIdType p = parts->GetValue(c);
        for (int k = 0; k < 4; ++k)
        {
          EXPECT(colors->GetTypedComponent(c, k) == partColors->GetTypedComponent(p, k));
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
  EXPECT(triangles > 98000 && triangles < 102000);
  EXPECT(source->GetOutput()->GetFieldData()->GetAbstractArray("PartNames")->GetNumberOfTuples() ==
    64);
  EXPECT(!source->SetSceneByName("no-such-scene"));
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
