// vtkOctreeCuller UPDATE_ON_EVENTS (event-driven dirty tracking): props are moved, transformed
// and their geometry regenerated between frames in every way the class documentation lists as
// detected; every frame the culler's drawn set must contain
//  - the exact visible set of the ID buffer (the props' current world geometry, merged), and
//  - the props a fresh UPDATE_BOUNDS_EVERY_FRAME culler draws (same hierarchy test on fresh
//    bounds: also catches props that are in the frustum but hidden).
// Also: props another culler removed stay observed and are re-read when they are back if they
// changed; props that leave the renderer stop being observed; deleting the culler removes its
// observers (the objects live on and can be modified without a crash).
#include "vtkOctreeCuller.h"

#include "scenevis/testing/IdBuffer.h"
#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/StrictVtkOutput.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCubeSource.h>
#include <vtkCullerCollection.h>
#include <vtkFollower.h>
#include <vtkIdTypeArray.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSphereSource.h>
#include <vtkTransform.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <random>
#include <string>
#include <vector>

namespace
{
namespace st = scenevis::testing;

bool Check(bool ok, const std::string& what)
{
  std::cout << (ok ? "ok   " : "FAIL ") << what << "\n";
  return ok;
}

/// Each actor's current world geometry (mapper input after Update, through the actor matrix),
/// merged, with the actor index as cell data "ActorId".
vtkSmartPointer<vtkPolyData> WorldGeometry(const std::vector<vtkSmartPointer<vtkActor>>& actors,
  const std::vector<bool>& present)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkIdTypeArray> ids;
  ids->SetName("ActorId");
  for (std::size_t a = 0; a < actors.size(); ++a)
  {
    vtkActor* actor = actors[a];
    if (!present[a] || !actor->GetMapper())
    {
      continue;
    }
    actor->GetMapper()->Update();
    vtkPolyData* pd = vtkPolyData::SafeDownCast(actor->GetMapper()->GetInputDataObject(0, 0));
    if (!pd || !pd->GetPoints())
    {
      continue;
    }
    vtkMatrix4x4* m = actor->GetMatrix();
    const vtkIdType base = points->GetNumberOfPoints();
    for (vtkIdType i = 0; i < pd->GetNumberOfPoints(); ++i)
    {
      double p[4] = { 0, 0, 0, 1 }, q[4];
      pd->GetPoint(i, p);
      m->MultiplyPoint(p, q);
      points->InsertNextPoint(q[0] / q[3], q[1] / q[3], q[2] / q[3]);
    }
    vtkCellArray* cells = pd->GetPolys();
    vtkIdType npts = 0;
    const vtkIdType* pts = nullptr;
    std::vector<vtkIdType> cell;
    for (cells->InitTraversal(); cells->GetNextCell(npts, pts);)
    {
      cell.assign(pts, pts + npts);
      for (vtkIdType& id : cell)
      {
        id += base;
      }
      polys->InsertNextCell(npts, cell.data());
      ids->InsertNextValue(static_cast<vtkIdType>(a));
    }
  }
  vtkNew<vtkPolyData> out;
  out->SetPoints(points);
  out->SetPolys(polys);
  out->GetCellData()->AddArray(ids);
  return out;
}

std::vector<std::uint32_t> Drawn(vtkOctreeCuller* culler, vtkRenderer* ren,
  const std::vector<vtkSmartPointer<vtkActor>>& actors, const std::vector<bool>& present)
{
  std::vector<vtkProp*> list;
  for (std::size_t a = 0; a < actors.size(); ++a)
  {
    if (present[a])
    {
      list.push_back(actors[a]);
    }
  }
  int length = static_cast<int>(list.size()), initialized = 0;
  culler->Cull(ren, list.data(), length, initialized);
  std::vector<std::uint32_t> drawn;
  for (int i = 0; i < length; ++i)
  {
    const auto it = std::find(actors.begin(), actors.end(), list[static_cast<std::size_t>(i)]);
    drawn.push_back(static_cast<std::uint32_t>(it - actors.begin()));
  }
  std::sort(drawn.begin(), drawn.end());
  return drawn;
}
} // namespace

int TestOctreeCullerEvents(int, char*[])
{
  st::StrictVtkOutput vtkOutput;
  bool ok = true;
  vtkSmartPointer<vtkRenderWindow> window = st::MakeRenderWindow(300, 200);
  vtkSmartPointer<vtkRenderWindow> idWindow = st::MakeRenderWindow(300, 200);
  vtkNew<vtkRenderer> ren;
  window->AddRenderer(ren);
  ren->GetCullers()->RemoveAllItems();
  auto culler = vtkSmartPointer<vtkOctreeCuller>::New();
  ok &= Check(culler->GetUpdateMode() == vtkOctreeCuller::UPDATE_ON_EVENTS,
    "UPDATE_ON_EVENTS is the default");
  vtkNew<vtkOctreeCuller> reference;
  reference->SetUpdateMode(vtkOctreeCuller::UPDATE_BOUNDS_EVERY_FRAME);
  ren->AddCuller(culler);

  // The scene: 160 actors in a 40 x 40 x 10 box; the camera sees about a third of it.
  std::mt19937_64 gen(99);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto where = [&]() { return std::vector<double>{ 40 * u(gen) - 20, 40 * u(gen) - 20, 10 * u(gen) }; };
  const int count = 160;
  std::vector<vtkSmartPointer<vtkActor>> actors;
  std::vector<vtkSmartPointer<vtkCubeSource>> cubes;       // own source per actor (pipeline)
  std::vector<vtkSmartPointer<vtkPolyData>> datas;         // own polydata (SetInputData)
  std::vector<vtkSmartPointer<vtkMatrix4x4>> matrices;
  std::vector<vtkSmartPointer<vtkTransform>> transforms, transformInputs;
  vtkNew<vtkSphereSource> shared; // shared by a group of actors
  shared->SetRadius(0.7);
  std::vector<int> kind(count);
  std::vector<bool> present(count, true);
  for (int a = 0; a < count; ++a)
  {
    vtkNew<vtkPolyDataMapper> mapper;
    vtkSmartPointer<vtkActor> actor;
    kind[a] = a % 6;
    if (kind[a] == 5)
    {
      actor = vtkSmartPointer<vtkFollower>::New(); // polled
      vtkFollower::SafeDownCast(actor)->SetCamera(ren->GetActiveCamera());
    }
    else
    {
      actor = vtkSmartPointer<vtkActor>::New();
    }
    auto cube = vtkSmartPointer<vtkCubeSource>::New();
    cubes.push_back(cube);
    vtkNew<vtkPolyData> data;
    {
      cube->Update();
      data->DeepCopy(cube->GetOutput());
    }
    datas.push_back(data);
    if (kind[a] == 1)
    {
      mapper->SetInputData(data);
    }
    else if (kind[a] == 2)
    {
      mapper->SetInputConnection(shared->GetOutputPort());
    }
    else
    {
      mapper->SetInputConnection(cube->GetOutputPort());
    }
    actor->SetMapper(mapper);
    const std::vector<double> p = where();
    actor->SetPosition(p[0], p[1], p[2]);
    matrices.push_back(vtkSmartPointer<vtkMatrix4x4>::New());
    auto input = vtkSmartPointer<vtkTransform>::New();
    auto transform = vtkSmartPointer<vtkTransform>::New();
    transform->SetInput(input);
    transformInputs.push_back(input);
    transforms.push_back(transform);
    if (kind[a] == 3)
    {
      actor->SetUserMatrix(matrices.back());
    }
    if (kind[a] == 4)
    {
      actor->SetUserTransform(transform); // polled
    }
    ren->AddActor(actor);
    actors.push_back(actor);
  }
  vtkCamera* cam = ren->GetActiveCamera();
  cam->SetPosition(0, -45, 25);
  cam->SetFocalPoint(0, 0, 3);
  cam->SetViewUp(0, 0, 1);
  cam->SetViewAngle(35);
  cam->SetClippingRange(1, 200);

  std::size_t missingEvs = 0, missingRef = 0, changes = 0, drawnSum = 0;
  const int frames = 60;
  for (int f = 0; f < frames; ++f)
  {
    // ~12 random changes per frame, of every detected kind.
    for (int k = 0; k < 12; ++k)
    {
      const int a = static_cast<int>(u(gen) * count) % count;
      const std::vector<double> p = where();
      vtkActor* actor = actors[static_cast<std::size_t>(a)];
      const int change = static_cast<int>(u(gen) * 12);
      ++changes;
      switch (change)
      {
        case 0:
          actor->SetPosition(p[0], p[1], p[2]);
          break;
        case 1:
          actor->RotateZ(40 * u(gen));
          actor->SetScale(0.5 + 3 * u(gen), 1, 1);
          break;
        case 2:
          actor->SetOrigin(p[0] * 0.3, p[1] * 0.3, 0);
          actor->RotateX(30);
          break;
        case 3: // regenerate geometry upstream (also of culled props)
          cubes[static_cast<std::size_t>(a)]->SetCenter(p[0] * 0.5, p[1] * 0.5, p[2] * 0.5);
          cubes[static_cast<std::size_t>(a)]->SetXLength(0.5 + 3 * u(gen));
          break;
        case 4: // edit the points of SetInputData polydata, then Modified() on the points
        {
          vtkPoints* pts = datas[static_cast<std::size_t>(a)]->GetPoints();
          for (vtkIdType i = 0; i < pts->GetNumberOfPoints(); ++i)
          {
            double q[3];
            pts->GetPoint(i, q);
            pts->SetPoint(i, q[0] + p[0] * 0.2, q[1] + p[1] * 0.2, q[2]);
          }
          pts->Modified();
          break;
        }
        case 5: // the same through the points' array only
        {
          vtkDataArray* array = datas[static_cast<std::size_t>(a)]->GetPoints()->GetData();
          for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
          {
            array->SetComponent(i, 2, array->GetComponent(i, 2) + p[2] - 5);
          }
          array->Modified();
          break;
        }
        case 6: // replace the points
        {
          vtkNew<vtkPoints> pts;
          pts->DeepCopy(datas[static_cast<std::size_t>(a)]->GetPoints());
          for (vtkIdType i = 0; i < pts->GetNumberOfPoints(); ++i)
          {
            double q[3];
            pts->GetPoint(i, q);
            pts->SetPoint(i, q[0] - p[0] * 0.1, q[1], q[2]);
          }
          datas[static_cast<std::size_t>(a)]->SetPoints(pts);
          break;
        }
        case 7: // user matrix elements
          matrices[static_cast<std::size_t>(a)]->SetElement(0, 3, p[0]);
          matrices[static_cast<std::size_t>(a)]->SetElement(1, 3, p[1]);
          break;
        case 8: // user transform through its input (no event on the transform itself)
          transformInputs[static_cast<std::size_t>(a)]->Identity();
          transformInputs[static_cast<std::size_t>(a)]->Translate(p[0], p[1], 0);
          break;
        case 9: // the shared source (moves a whole group)
          if (u(gen) < 0.3)
          {
            shared->SetCenter(p[0] * 0.3, p[1] * 0.3, p[2]);
          }
          break;
        case 10: // a new input
        {
          vtkNew<vtkCubeSource> fresh;
          fresh->SetCenter(p[0] * 0.2, p[1] * 0.2, 0);
          fresh->Update();
          vtkNew<vtkPolyData> pd;
          pd->DeepCopy(fresh->GetOutput());
          datas[static_cast<std::size_t>(a)] = pd;
          vtkPolyDataMapper::SafeDownCast(actor->GetMapper())->SetInputData(pd);
          break;
        }
        default: // remove / re-add
          present[static_cast<std::size_t>(a)] = !present[static_cast<std::size_t>(a)];
          break;
      }
    }
    const std::vector<std::uint32_t> drawn = Drawn(culler, ren, actors, present);
    const std::vector<std::uint32_t> fresh = Drawn(reference, ren, actors, present);
    drawnSum += drawn.size();
    const st::IdImage evs =
      st::RenderVisibleIds(idWindow, WorldGeometry(actors, present), cam, "ActorId");
    const st::CullingCheck check = st::CullingIsConservative(evs, drawn);
    const st::CullingCheck checkRef = st::CullingIsConservative(fresh, drawn);
    missingEvs += check.missing.size();
    missingRef += checkRef.missing.size();
    if (!check.conservative || !checkRef.conservative)
    {
      std::cout << "frame " << f << ": EVS " << check.Summary() << "; fresh bounds "
                << checkRef.Summary() << "\n";
    }
    if (f % 10 == 0)
    {
      window->Render(); // through the renderer too (mappers update their pipelines)
    }
  }
  std::cout << frames << " frames, " << changes << " changes; drawn " << drawnSum << " of "
            << frames * count << "; observed objects " << culler->GetNumberOfObservedObjects()
            << ", polled props " << culler->GetNumberOfPolledProps() << ", rebuilds "
            << culler->GetNumberOfRebuilds() << "\n";
  ok &= Check(missingEvs == 0, "0 false negatives against the ID-buffer EVS (" +
      std::to_string(missingEvs) + ")");
  ok &= Check(missingRef == 0, "0 props missing against fresh bounds (" +
      std::to_string(missingRef) + ")");
  ok &= Check(drawnSum < static_cast<std::size_t>(frames * count), "something is culled");
  ok &= Check(culler->GetNumberOfPolledProps() > 0 &&
      culler->GetNumberOfPolledProps() < count / 2,
    "followers and user-transform actors polled, the others on events");

  // Props that another culler removed from the list stay observed (re-observing and re-reading
  // them every frame cost more than the cull behind vtkPortalCuller); what happens to them
  // meanwhile is read when they are back. Props that leave the renderer stop being observed.
  {
    std::vector<bool> all(count, true), few(count, false);
    for (int a = 0; a < count; a += 2)
    {
      few[static_cast<std::size_t>(a)] = true; // half stay: mapped without a rebuild
    }
    // Actor 1 out of view, read so while in the list; then it leaves the list.
    actors[1]->SetPosition(0, 0, -500);
    Drawn(culler, ren, actors, all);
    const vtkIdType rebuilds = culler->GetNumberOfRebuilds();
    const vtkIdType before = culler->GetNumberOfObservedObjects();
    Drawn(culler, ren, actors, few);
    ok &= Check(culler->GetNumberOfObservedObjects() == before,
      "props another culler removed stay observed (" + std::to_string(before) + " -> " +
        std::to_string(culler->GetNumberOfObservedObjects()) + ")");
    // Moved into view while out of the list, for two frames: drawn when it comes back.
    actors[1]->SetPosition(0, 0, 3);
    Drawn(culler, ren, actors, few);
    std::vector<bool> back = few;
    back[1] = true;
    std::vector<std::uint32_t> drawn = Drawn(culler, ren, actors, back);
    ok &= Check(std::find(drawn.begin(), drawn.end(), 1u) != drawn.end(),
      "a prop moved while out of the list is drawn when it comes back");
    // Out of the list and unchanged: drawn again when back, with no re-read needed.
    Drawn(culler, ren, actors, few);
    drawn = Drawn(culler, ren, actors, back);
    ok &= Check(std::find(drawn.begin(), drawn.end(), 1u) != drawn.end(),
      "a prop back in the list unchanged is drawn");
    // The odd props leave the renderer: their observers go at the next Cull() (the list
    // changes: without actor 1).
    for (int a = 1; a < count; a += 2)
    {
      ren->RemoveActor(actors[static_cast<std::size_t>(a)]);
    }
    Drawn(culler, ren, actors, few);
    const vtkIdType after = culler->GetNumberOfObservedObjects();
    std::cout << "observed objects: " << before << " -> " << after
              << " after half the props left the renderer\n";
    ok &= Check(after < before && culler->GetNumberOfRebuilds() == rebuilds,
      "observers of props that left the renderer are removed, without a rebuild");
    for (int a = 1; a < count; a += 2)
    {
      ren->AddActor(actors[static_cast<std::size_t>(a)]);
    }
  }

  // Switching modes: observers removed, and re-added (with a full re-read) when switched back.
  culler->SetUpdateMode(vtkOctreeCuller::UPDATE_MANUAL);
  Drawn(culler, ren, actors, present);
  ok &= Check(culler->GetNumberOfObservedObjects() == 0, "other modes observe nothing");
  actors[2]->SetPosition(0, 0, 3);
  culler->SetUpdateMode(vtkOctreeCuller::UPDATE_ON_EVENTS);
  present[2] = true;
  const std::vector<std::uint32_t> drawn = Drawn(culler, ren, actors, present);
  ok &= Check(std::find(drawn.begin(), drawn.end(), 2u) != drawn.end() &&
      culler->GetNumberOfObservedObjects() > 0,
    "switched back to events: re-read and observed");

  // The culler goes first: the objects it observed must not call into it afterwards.
  ren->GetCullers()->RemoveAllItems();
  culler = nullptr;
  for (int a = 0; a < count; ++a)
  {
    actors[static_cast<std::size_t>(a)]->SetPosition(1, 2, 3);
    matrices[static_cast<std::size_t>(a)]->SetElement(2, 3, 1.0);
    cubes[static_cast<std::size_t>(a)]->SetCenter(1, 1, 1);
  }
  shared->SetCenter(0, 0, 0);
  ok &= Check(true, "objects modified after the culler was deleted: no call into it");
  return vtkOutput.ExitCode(ok ? EXIT_SUCCESS : EXIT_FAILURE);
}
