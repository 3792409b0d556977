/**
 * @class   vtkScenePlanInstaller
 * @brief   Puts vtkSceneVisPlanner's choice into a renderer: the culler, the translucent pass
 *          and the mappers of the actors, and takes them out again.
 *
 * Private to the RenderingAuto module (not a vtkObject, not wrapped). What it installs is kept
 * for re-use: one vtkOcclusionCuller for "octree" and "occlusion" (switching keeps its
 * hierarchy), one vtkPortalCuller for "portals" (its room graph and PVS), one BSP-sorted or
 * chunked mapper per actor (their trees and chunks). It replaces
 * only what it knows: VTK's vtkFrustumCoverageCuller (our culler does its work), no pass or its
 * own pass (a renderer with a pass of the application's keeps it, with one warning), plain
 * vtkOpenGLPolyDataMapper mappers (an application's own mapper class is left alone). A mapper the
 * application sets on an actor wins over the one installed there. Uninstall() restores it all.
 *
 * @sa vtkSceneVisPlanner vtkScenePlanInventory
 */

#ifndef vtkScenePlanInstaller_h
#define vtkScenePlanInstaller_h

#include "vtkNew.h"
#include "vtkScenePlanInventory.h"
#include "vtkScenePlanRooms.h"
#include "vtkSmartPointer.h"
#include "vtkType.h"
#include "vtkWeakPointer.h"

#include <string>
#include <unordered_map>
#include <vector>

class vtkActor;
class vtkBSPSortedPolyDataMapper;
class vtkBSPTranslucentPass;
class vtkChunkedPolyDataMapper;
class vtkCuller;
class vtkMapper;
class vtkObject;
class vtkOcclusionCuller;
class vtkOrderedTranslucentPass;
class vtkPolyData;
class vtkPortalCuller;
class vtkRenderPass;
class vtkRenderer;

class vtkScenePlanInstaller
{
public:
  /// @p owner: the object warnings are given for.
  explicit vtkScenePlanInstaller(vtkObject* owner);
  ~vtkScenePlanInstaller();
  vtkScenePlanInstaller(const vtkScenePlanInstaller&) = delete;
  vtkScenePlanInstaller& operator=(const vtkScenePlanInstaller&) = delete;

  /// Installs the culling method @p cull ("octree", "occlusion", "portals", "chunked", "none") and
  /// the translucency method @p translucency ("multi-actor", "bsp-mapper", ...) for the actors of
  /// @p inventory: the BSP mapper on translucent actors, chunks in opaque ones of at least
  /// @p chunkedMinimumTriangles triangles. Entries whose mapper it changed get their ActorTime
  /// updated (the change is its own, not the application's). Swapped actors that left the
  /// inventory get their own mapper back.
  void Install(vtkRenderer* ren, const std::string& cull, const std::string& translucency,
    vtkScenePlanInventory& inventory, vtkIdType chunkedMinimumTriangles);
  /// The portals and room array name the portal culler gets ("portals" culling).
  void SetPortals(vtkPolyData* portals, const char* roomIdArrayName);
  /// The rooms of the cells of actors, given to the portal culler apart from their data
  /// (vtkPortalCuller::SetPropCellRooms; rooms the planner generated). Replaces the previous ones.
  void SetCellRooms(const vtkScenePlanRooms::CellRooms& rooms);
  /// Takes everything out of @p ren (may be null: a renderer being deleted is not touched) and
  /// gives the actors their own mappers back.
  void Uninstall(vtkRenderer* ren);

  /// The mapper the application gave @p actor (not one installed here).
  vtkMapper* ApplicationMapper(vtkActor* actor);
  /// Whether @p mapper is one the installer may replace (a plain vtkOpenGLPolyDataMapper).
  static bool IsPlainPolyDataMapper(vtkMapper* mapper);

  /// The culler, when installed.
  vtkCuller* GetCuller() const;
  /// The pass, when installed.
  vtkRenderPass* GetPass() const { return this->InstalledPass; }
  /// Actors drawn by a mapper installed here.
  int GetNumberOfSwappedMappers() const;

private:
  /// A mapper installed on an application's actor, and the actor's own.
  struct MapperSwap
  {
    vtkWeakPointer<vtkActor> Actor;
    vtkSmartPointer<vtkMapper> Original;
    vtkSmartPointer<vtkBSPSortedPolyDataMapper> Sorted; ///< kept for re-use (its tree)
    vtkSmartPointer<vtkChunkedPolyDataMapper> Chunked;  ///< kept for re-use (its chunks)
    vtkMapper* Installed = nullptr;                     ///< Sorted, Chunked or nullptr
    vtkMTimeType CopiedTime = 0;                        ///< Original's MTime when copied
  };

  void InstallCuller(vtkRenderer* ren, const std::string& cull);
  /// Hands CellRooms to the portal culler, when there is one.
  void GiveCellRooms();
  /// Puts @p wanted (or none) in place of VTK's coverage culler and of the other culler of ours.
  void PlaceCuller(vtkRenderer* ren, vtkCuller* wanted);
  void InstallPass(vtkRenderer* ren, vtkRenderPass* pass);
  void SwapMapper(vtkActor* actor, bool sorted, bool chunked);

  vtkObject* Owner;
  vtkSmartPointer<vtkOcclusionCuller> Culler;
  vtkSmartPointer<vtkPortalCuller> PortalCuller;
  vtkCuller* Installed = nullptr; ///< Culler, PortalCuller or nullptr
  vtkSmartPointer<vtkPolyData> Portals;
  std::string RoomIdArrayName = "RoomId";
  vtkScenePlanRooms::CellRooms CellRooms;
  std::vector<vtkSmartPointer<vtkCuller>> RemovedCullers;
  vtkSmartPointer<vtkOrderedTranslucentPass> OrderedPass; ///< with vtkBSPTranslucentPass
  vtkSmartPointer<vtkBSPTranslucentPass> SortedPass;
  vtkSmartPointer<vtkOrderedTranslucentPass> PlainPass; ///< for the BSP mapper
  vtkRenderPass* InstalledPass = nullptr;
  std::unordered_map<vtkActor*, MapperSwap> Swaps;
  bool WarnedPass = false;
};

#endif
// VTK-HeaderTest-Exclude: vtkScenePlanInstaller.h
