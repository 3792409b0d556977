/**
 * @class   vtkDemoSceneSource
 * @brief   The deterministic SceneVis demo scenes (scenevis/Scenes.h) as polydata.
 *
 * One merged mesh per scene, with cell data that keeps the scene's parts apart:
 * - "PartId" (vtkIdTypeArray): the part of every polygon;
 * - "Colors" (RGBA unsigned char, set as the active scalars): the part's colour and opacity, so a
 *   mapper with direct scalars shows translucent parts translucent.
 * For SCENE_BUILDING, also "RoomId" (int; -1 outside). Part names, colours and opacities are in
 * the field data arrays "PartNames", "PartColors" (RGBA, one tuple per part).
 *
 * Scenes:
 * - SCENE_SPHERE_GRID: 4x4x4 overlapping translucent spheres (radius 0.8, spacing 1), about
 *   TriangleCount triangles in all: the standard hard translucency scene (default).
 * - SCENE_CYCLIC_QUADS: three quads overlapping in a cycle (viewed from +z).
 * - SCENE_INTERPENETRATING_TRIANGLES: two triangles that pierce each other.
 * - SCENE_CAD_ASSEMBLY: PartCount closed CAD-like parts, about TriangleCount triangles in all.
 * - SCENE_BUILDING: Floors x RoomsX x RoomsY rooms with doors, windows, stairs and furniture.
 *
 * Points are double precision (the generators work in double; Origin shifts the CAD assembly).
 *
 * Pieces (parallel pipelines, e.g. ParaView's MPI ranks): piece i of n holds whole parts, a
 * contiguous run of PartIds balanced by polygons, and only the points they use; PartId keeps
 * its scene-wide value and the field data stays whole. A piece may be empty (more pieces than
 * parts; a piece number outside [0, n) is empty too). The scene is generated whole on every
 * piece, then cut.
 *
 * @sa vtkDemoScenePortals.h (the building's portals, for vtkPortalCuller)
 */

#ifndef vtkDemoSceneSource_h
#define vtkDemoSceneSource_h

#include "SceneVisFiltersSourcesModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

class SCENEVISFILTERSSOURCES_EXPORT vtkDemoSceneSource : public vtkPolyDataAlgorithm
{
public:
  static vtkDemoSceneSource* New();
  vtkTypeMacro(vtkDemoSceneSource, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Scenes
  {
    SCENE_SPHERE_GRID = 0,
    SCENE_CYCLIC_QUADS,
    SCENE_INTERPENETRATING_TRIANGLES,
    SCENE_CAD_ASSEMBLY,
    SCENE_BUILDING
  };

  vtkSetClampMacro(Scene, int, SCENE_SPHERE_GRID, SCENE_BUILDING);
  vtkGetMacro(Scene, int);
  /// Set the scene by name: spheres, cyclic-quads, triangles, cad, building. False if unknown.
  bool SetSceneByName(const char* name);
  static const char* GetSceneName(int scene);

  ///@{
  /**
   * Scene size. Values below the minimum (or above the maximum) are clamped, with a warning.
   * TriangleCount: approximate total triangles of the spheres and CAD scenes (>= 64, default
   * 20,000). PartCount: parts of the CAD assembly (1 to 10^7, default 1,000). Floors, RoomsX,
   * RoomsY: building size (1 to 1000 each, defaults 3 x 4 x 3).
   */
  virtual void SetTriangleCount(vtkIdType count);
  vtkGetMacro(TriangleCount, vtkIdType);
  virtual void SetPartCount(vtkIdType count);
  vtkGetMacro(PartCount, vtkIdType);
  virtual void SetFloors(int count);
  vtkGetMacro(Floors, int);
  virtual void SetRoomsX(int count);
  vtkGetMacro(RoomsX, int);
  virtual void SetRoomsY(int count);
  vtkGetMacro(RoomsY, int);
  ///@}

  /**
   * The largest scene generated, in (estimated) triangles: a larger request is refused up front
   * with one error and an empty output, instead of running the machine out of memory (a
   * generated triangle costs about 100 bytes at its peak). Default 100,000,000.
   */
  vtkSetClampMacro(MaximumTriangleCount, vtkIdType, 1, VTK_ID_MAX);
  vtkGetMacro(MaximumTriangleCount, vtkIdType);

  vtkSetMacro(Seed, unsigned int);
  vtkGetMacro(Seed, unsigned int);
  /// Translation of the CAD assembly (to test precision far from the origin).
  vtkSetVector3Macro(Origin, double);
  vtkGetVector3Macro(Origin, double);

protected:
  vtkDemoSceneSource();
  ~vtkDemoSceneSource() override = default;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /// The size of the scene the settings ask for, in triangles (an estimate for CAD and building).
  vtkIdType EstimatedTriangleCount() const;

  int Scene = SCENE_SPHERE_GRID;
  vtkIdType TriangleCount = 20000;
  vtkIdType PartCount = 1000;
  int Floors = 3;
  int RoomsX = 4;
  int RoomsY = 3;
  unsigned int Seed = 1;
  vtkIdType MaximumTriangleCount = 100000000;
  double Origin[3] = { 0.0, 0.0, 0.0 };

private:
  vtkDemoSceneSource(const vtkDemoSceneSource&) = delete;
  void operator=(const vtkDemoSceneSource&) = delete;
};

#endif
