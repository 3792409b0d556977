/**
 * @class   vtkScenePlanRoomsModel
 * @brief   What a generation of rooms for vtkSceneVisPlanner sees of the scene: the counted
 *          actors' polygons and strips in world coordinates, copied into one model of its own,
 *          and how the rooms of that model's cells go back to each actor's cells.
 *
 * Private to the RenderingAuto module (a plain value, not a vtkObject). Gather() reads the
 * application's actors and data on the render thread and copies them (points transformed by each
 * actor's matrix, cells renumbered): the model shares no VTK object with the application, so it
 * may be handed to another thread (vtkScenePlanRoomsWorker) and nothing there touches what the
 * application renders. CellRoomsOf() turns the rooms of the model's cells back into each actor's
 * cell rooms; it reads only the counts taken by Gather(), not the actors' data.
 *
 * @sa vtkScenePlanRooms vtkScenePlanRoomsWorker vtkAutoRooms
 */

#ifndef vtkScenePlanRoomsModel_h
#define vtkScenePlanRoomsModel_h

#include "vtkScenePlanRooms.h" // For vtkScenePlanRooms::CellRooms

#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <vector>

class vtkActor;
class vtkIntArray;
class vtkScenePlanInventory;

struct vtkScenePlanRoomsModel
{
  /// One actor's share of the model: its cells in vtkPolyData's order (vertices, lines,
  /// polygons, strips) and where its polygons and strips start among the model's.
  struct Piece
  {
    vtkActor* Actor = nullptr;
    vtkIdType Verts = 0;
    vtkIdType Lines = 0;
    vtkIdType Polys = 0;
    vtkIdType Strips = 0;
    vtkIdType FirstPoly = 0;
    vtkIdType FirstStrip = 0;
  };

  /// Points (double, world coordinates), polygons, then strips: no other cells, no arrays. Whoever
  /// generates may take it (the worker thread owns it then); CellRoomsOf() does not need it.
  vtkSmartPointer<vtkPolyData> Model;
  std::vector<Piece> Pieces;
  vtkIdType ModelPolys = 0; ///< the model's polygons: its strips' rooms follow theirs
  vtkIdType ModelStrips = 0;

  /// The counted actors of @p inventory that have polydata with points, as one model.
  static vtkScenePlanRoomsModel Gather(vtkScenePlanInventory& inventory);

  /**
   * Every piece's actor with the room of each of its cells ("RoomId" int arrays): -1 for
   * vertices and lines, @p rooms (one value per cell of Model: polygons, then strips) for the
   * rest.
   */
  vtkScenePlanRooms::CellRooms CellRoomsOf(vtkIntArray* rooms) const;
};

#endif
