/**
 * @file Scenes.h
 * @brief Small deterministic test scenes shared by tests, tools and examples.
 */
#ifndef scenevis_testing_Scenes_h
#define scenevis_testing_Scenes_h

#include <vtkDemoScenePortals.h>
#include <vtkSmartPointer.h>

class vtkActor;
class vtkAlgorithm;
class vtkCubeSource;
class vtkPolyData;
class vtkRenderer;
class vtkSphereSource;
class vtkTriangleFilter;

namespace scenevis
{
namespace scenes
{
struct BuildingScene;
}
}

namespace scenevis
{
namespace testing
{

/// How translucent geometry is composited.
enum class Translucency
{
  DepthPeeling, ///< VTK's depth peeling (order independent, exact up to the peel count)
  OrderedAlpha, ///< plain alpha blending in primitive order (EnableOrderedAlphaBlending)
  VtkDefault    ///< VTK 9.1's default: weighted-average OIT (order independent, approximate)
};

/// Parameters of MakeSphereGridRenderer(); the defaults are the standard demo scene.
struct SphereGridOptions
{
  int count = 4;       ///< spheres per axis (count^3 spheres)
  double radius = 0.8; ///< overlapping neighbours at spacing 1
  double spacing = 1.0;
  double opacity = 0.3; ///< 1: opaque scene
  int resolution = 16;  ///< theta and phi resolution of vtkSphereSource
  Translucency translucency = Translucency::DepthPeeling;
  int maximumPeels = 16; ///< for DepthPeeling (occlusion ratio 0: peel until done or max)
};

/**
 * A renderer with count^3 vtkSphereSource spheres on a regular grid, one actor each, coloured by
 * grid position, black background, a fixed oblique camera (azimuth 30, elevation 20, reset to the
 * bounds), default lighting and the requested translucency mode.
 */
vtkSmartPointer<vtkRenderer> MakeSphereGridRenderer(
  const SphereGridOptions& options = SphereGridOptions());

/// An axis-aligned square quad (one 4-point polygon) at depth @p z, from (x0,y0) to (x1,y1).
vtkSmartPointer<vtkPolyData> MakeQuad(double x0, double y0, double x1, double y1, double z);

/**
 * A closed, non-convex surface centred at the origin: a vtkSphereSource of radius @p radius
 * (48 x 32) whose points are moved along their radius by a factor 1 + 0.15 sin(7 theta) sin(5 phi).
 * Seen from outside its polygons hide each other, so a BSP tree splits it (ordered leaves keep
 * many of them whole).
 */
vtkSmartPointer<vtkPolyData> MakeBumpySphere(double radius = 1.5);

/// The polygons of @p a followed by those of @p b (cell order preserved), in one polydata.
vtkSmartPointer<vtkPolyData> AppendPolygons(vtkPolyData* a, vtkPolyData* b);

/// The portals of a building in vtkPortalCuller's format (SceneVis::FiltersSources).
using scenevis::MakePortalPolyData;

/// The polygons of @p building whose room is @p room (all rooms when @p room < -1; -1 is the
/// outside), with an integer cell array "RoomNode": the polygon's room, or @p outsideNode for the
/// outside (an id for the ID buffer, where -1 cannot be one).
vtkSmartPointer<vtkPolyData> MakeRoomPolyData(
  const scenevis::scenes::BuildingScene& building, int room, int outsideNode);

/// An actor drawing @p source's output in colour (r, g, b) at @p opacity, without specular.
vtkSmartPointer<vtkActor> MakeTranslucentActor(
  vtkAlgorithm* source, double r, double g, double b, double opacity);

/// Three interpenetrating translucent actors of different colours, the scene of the
/// order-across-actors tests: a red sphere (opacity 0.45), a blue sphere (0.35) and a green slab
/// (0.5, rotated 20 degrees about z) cutting both. The sources stay for more actors of the same
/// shapes (slabTriangles: the slab as triangles).
struct InterpenetratingActors
{
  vtkSmartPointer<vtkSphereSource> sphereA, sphereB;
  vtkSmartPointer<vtkCubeSource> slab;
  vtkSmartPointer<vtkTriangleFilter> slabTriangles;
  vtkSmartPointer<vtkActor> red, blue, green;
};
InterpenetratingActors MakeInterpenetratingActors();

} // namespace testing
} // namespace scenevis

#endif
