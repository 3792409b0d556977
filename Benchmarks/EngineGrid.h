// The real-CAD benchmark scene of scenevis_occlusion_bench and scenevis_soak_bench: the
// 2CylinderEngine glTF (Debian's assimp-testmodels: 115 parts, 121,496 triangles, real degenerate
// triangles) split into its parts in one pass over the cells, then instanced on an N x N grid of
// engines in x and z (glTF is y-up), 15 % apart: the actors of a part share its mapper, each
// engine is placed by the actors' positions. Opaque (each part gets its glTF colour at opacity 1).
// The same grid can be flattened into ONE polydata, as flattening exporters write it.
#ifndef scenevis_bench_EngineGrid_h
#define scenevis_bench_EngineGrid_h

#include <vtkActor.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkType.h>

#include <string>
#include <vector>

namespace scenevis
{
namespace bench
{

/// One part of the engine: its own compact points and polygons, and the colour of its first cell.
struct EnginePart
{
  vtkSmartPointer<vtkPolyData> data;
  double colour[3] = { 0.8, 0.8, 0.8 };
};

/// The engine read from the data cache and split into its parts.
struct EngineModel
{
  std::vector<EnginePart> parts;
  double readSeconds = 0.0;
  double splitSeconds = 0.0;
};

/// Reads `engine-glb` from the data cache into @p model. Returns 0 when it did, 77 (CTest's
/// SKIP_RETURN_CODE; "SKIPPED: ..." printed on stdout) when the data cache lacks it, 1 when it
/// cannot be read (the reason on stderr).
int LoadEngine(EngineModel& model);

/// The cells of @p model grouped by its "PartId" cell array into one polydata per part, in one
/// pass over the cells (each part gets its own compact points), with the "Colors" of its first
/// cell. Parts without polygons are left out.
std::vector<EnginePart> SplitParts(vtkPolyData* model);

/// Distance between neighbouring engines along x, y and z: 1.15 x the engine's extent.
void EnginePitch(const std::vector<EnginePart>& parts, double pitch[3]);

/// Bounds of the @p n x @p n grid of engines (of BuildEngineGrid() and FlattenEngineGrid()).
void EngineGridBounds(const std::vector<EnginePart>& parts, int n, double bounds[6]);

/// @p n x @p n engines as actors of one renderer (one actor per placed part).
struct EngineGrid
{
  vtkNew<vtkRenderer> renderer;
  std::vector<vtkSmartPointer<vtkActor>> actors;
  /// Per actor: its look (the part's colour) and its ID look (flat, unlit colour = actor index + 1
  /// in 24 bits, for ID renders).
  std::vector<vtkSmartPointer<vtkProperty>> looks, idLooks;
  double bounds[6];
  double pitch[3];
  vtkIdType triangles = 0;
};

/// Fills @p g (empty) with @p n x @p n engines of @p parts.
void BuildEngineGrid(EngineGrid& g, const std::vector<EnginePart>& parts, int n);

/// The same @p n x @p n grid as ONE polydata (float points, the model's point normals): every
/// placed part's polygons, with a "PartId" cell array holding the index of the actor that
/// BuildEngineGrid() makes for it.
vtkSmartPointer<vtkPolyData> FlattenEngineGrid(const std::vector<EnginePart>& parts, int n);

} // namespace bench
} // namespace scenevis

#endif
