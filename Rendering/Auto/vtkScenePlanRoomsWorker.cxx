#include "vtkScenePlanRoomsWorker.h"

#include <chrono>
#include <exception>
#include <string>
#include <utility>

vtkScenePlanRoomsWorker::~vtkScenePlanRoomsWorker()
{
  this->Wait();
}

void vtkScenePlanRoomsWorker::Start(vtkSmartPointer<vtkPolyData> model, double budgetSeconds)
{
  // std::launch::async: a thread now, never deferred into the Take() of a later render.
  this->Result = std::async(std::launch::async,
    [model = std::move(model), budgetSeconds]() mutable
    {
      vtkAutoRooms rooms;
      try
      {
        rooms = vtkAutoRooms::Generate(model, "RoomId", budgetSeconds);
      }
      catch (const std::exception& e) // as data: the render thread's Take() must not throw
      {
        rooms = vtkAutoRooms();
        rooms.Tried = true;
        rooms.Reason = std::string("generating rooms and portals failed (") + e.what() +
          ") in the background, so not used";
      }
      model = nullptr; // released here, by the only thread that ever used it
      return rooms;
    });
}

bool vtkScenePlanRoomsWorker::IsDone() const
{
  return this->Result.valid() &&
    this->Result.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
}

void vtkScenePlanRoomsWorker::Wait() const
{
  if (this->Result.valid())
  {
    this->Result.wait();
  }
}

vtkAutoRooms vtkScenePlanRoomsWorker::Take()
{
  return this->Result.get();
}
