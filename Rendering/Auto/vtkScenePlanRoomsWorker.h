/**
 * @class   vtkScenePlanRoomsWorker
 * @brief   One generation of rooms (vtkAutoRooms) at a time on a thread of its own, so that
 *          vtkSceneVisPlanner's render does not wait for it.
 *
 * Private to the RenderingAuto module (not a vtkObject). Start() hands the worker a model that
 * nobody else holds (vtkScenePlanRoomsModel::Gather() made it) and returns at once; the thread
 * runs vtkAutoRooms::Generate on it (the architectural look's test, then the generation when it
 * passes) under the processor-time budget (the thread's own time: see
 * scenevis::portals::GenerationConfig::budgetSeconds), and touches nothing else: every VTK object
 * it sees is the model or made by the generation, and its warnings are caught by vtkAutoRooms as
 * data (the reason), not printed. The thread releases the model before it ends; the result's
 * objects are handed over through the future, so that the render thread owns them alone after
 * Take().
 *
 * A generation cannot be interrupted: its budget bounds it. The destructor waits for a running
 * one (at most the budget), so that the thread never outlives what owns it.
 *
 * @sa vtkScenePlanRooms vtkScenePlanRoomsModel
 */

#ifndef vtkScenePlanRoomsWorker_h
#define vtkScenePlanRoomsWorker_h

#include "vtkAutoRooms.h"

#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <future>

class vtkScenePlanRoomsWorker
{
public:
  vtkScenePlanRoomsWorker() = default;
  ~vtkScenePlanRoomsWorker();
  vtkScenePlanRoomsWorker(const vtkScenePlanRoomsWorker&) = delete;
  vtkScenePlanRoomsWorker& operator=(const vtkScenePlanRoomsWorker&) = delete;

  /**
   * Tests and generates rooms and portals for @p model (which the worker owns from now on)
   * within @p budgetSeconds of processor time (0: no limit). Only when not IsBusy().
   */
  void Start(vtkSmartPointer<vtkPolyData> model, double budgetSeconds);

  /// A generation was started and its result not taken yet (it may be done).
  bool IsBusy() const { return this->Result.valid(); }
  /// A generation was started and has ended: Take() does not wait.
  bool IsDone() const;
  /// Waits until the generation started has ended (returns at once when none runs).
  void Wait() const;
  /// The result of the generation started (waiting for it): the worker is free again.
  vtkAutoRooms Take();

private:
  std::future<vtkAutoRooms> Result;
};

#endif
