// Specification: a vtkInstancedActor draws its placements exactly as one vtkActor per placement
// (user matrix) would: the same image pixel for pixel, with no culler, under vtkOctreeCuller
// and under vtkOcclusionCuller; those cullers keep exactly the placements they keep of the
// per-actor scene (same boxes, same hierarchy), draw only those, and never lose a visible
// placement. Bad input (NaN or singular matrices, visible indices out of range, no placements)
// gives a clear VTK error and no crash.
#include "vtkInstancedActor.h"
#include "vtkOcclusionCuller.h"
#include "vtkOctreeCuller.h"

#include "scenevis/testing/ImageCompare.h"
#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/StrictVtkOutput.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCullerCollection.h>
#include <vtkFrustumCoverageCuller.h> // VTK_CULLER_SORT_*
#include <vtkImageData.h>
#include <vtkLogger.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSphereSource.h>
#include <vtkTransform.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <set>
#include <sstream>
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

/// Placement matrices: a 6 x 4 x 3 block of spheres, turned, scaled unevenly, one mirrored.
std::vector<std::vector<double>> Placements()
{
  std::vector<std::vector<double>> matrices;
  for (int z = 0; z < 3; ++z)
  {
    for (int y = 0; y < 4; ++y)
    {
      for (int x = 0; x < 6; ++x)
      {
        vtkNew<vtkTransform> t;
        t->Translate(1.5 * x, 1.5 * y, -2.0 * z);
        t->RotateY(17.0 * x + 5.0 * y);
        t->RotateX(11.0 * z);
        t->Scale(1.0 + 0.1 * x, 1.0, (x + y) % 5 == 0 ? -0.8 : 0.8);
        const double* m = t->GetMatrix()->GetData();
        matrices.emplace_back(m, m + 16);
      }
    }
  }
  return matrices;
}

struct Scene
{
  vtkSmartPointer<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  std::vector<vtkSmartPointer<vtkActor>> Actors; // per placement, or the one instanced actor
  vtkSmartPointer<vtkInstancedActor> Instanced;
};

/// @p culler: 0 none, 1 octree, 2 occlusion.
void Build(Scene& scene, bool instanced, int culler)
{
  scene.Window = st::MakeRenderWindow(300, 200);
  scene.Window->AddRenderer(scene.Renderer);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(12);
  sphere->Update();
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkProperty> property;
  property->SetColor(0.9, 0.5, 0.2);
  if (instanced)
  {
    scene.Instanced = vtkSmartPointer<vtkInstancedActor>::New();
    scene.Instanced->SetMapper(mapper);
    scene.Instanced->SetProperty(property);
    for (const auto& m : Placements())
    {
      scene.Instanced->AddPlacement(m.data());
    }
    scene.Renderer->AddActor(scene.Instanced);
  }
  else
  {
    for (const auto& m : Placements())
    {
      vtkNew<vtkMatrix4x4> matrix;
      matrix->DeepCopy(m.data());
      vtkNew<vtkActor> actor;
      actor->SetMapper(mapper);
      actor->SetProperty(property);
      actor->SetUserMatrix(matrix);
      scene.Renderer->AddActor(actor);
      scene.Actors.push_back(actor.Get());
    }
  }
  scene.Renderer->GetCullers()->RemoveAllItems();
  if (culler == 1)
  {
    scene.Renderer->AddCuller(vtkSmartPointer<vtkOctreeCuller>::New());
  }
  else if (culler == 2)
  {
    scene.Renderer->AddCuller(vtkSmartPointer<vtkOcclusionCuller>::New());
  }
}

/// Cameras: the whole block, down a row (most placements hidden), close up (most outside).
void SetCamera(vtkRenderer* ren, int view)
{
  vtkCamera* cam = ren->GetActiveCamera();
  const double eyes[3][3] = { { 4, 3, 14 }, { -1.3, 0, 0 }, { 2, 1, 2.5 } };
  const double focal[3][3] = { { 4, 2, -2 }, { 10, 0, 0 }, { 4, 3, -4 } };
  cam->SetPosition(eyes[view]);
  cam->SetFocalPoint(focal[view]);
  cam->SetViewUp(0, 1, 0);
  cam->SetViewAngle(40);
  ren->ResetCameraClippingRange();
}

/// The props the culler of @p scene keeps for its camera (a copy of the list culled again).
std::set<vtkIdType> Kept(Scene& scene)
{
  auto* culler = vtkOctreeCuller::SafeDownCast(scene.Renderer->GetCullers()->GetItemAsObject(0));
  std::set<vtkIdType> kept;
  std::vector<vtkProp*> list(scene.Actors.begin(), scene.Actors.end());
  if (scene.Instanced)
  {
    list.assign(1, scene.Instanced);
  }
  int length = static_cast<int>(list.size());
  int initialized = 0;
  culler->Cull(scene.Renderer, list.data(), length, initialized);
  if (scene.Instanced)
  {
    for (vtkIdType k = 0; length > 0 && k < scene.Instanced->GetNumberOfVisiblePlacements(); ++k)
    {
      kept.insert(scene.Instanced->GetVisiblePlacement(k));
    }
    return kept;
  }
  for (int i = 0; i < length; ++i)
  {
    for (std::size_t a = 0; a < scene.Actors.size(); ++a)
    {
      if (scene.Actors[a] == list[i])
      {
        kept.insert(static_cast<vtkIdType>(a));
      }
    }
  }
  return kept;
}

std::string Ids(const std::set<vtkIdType>& ids)
{
  std::ostringstream out;
  for (const vtkIdType id : ids)
  {
    out << id << " ";
  }
  return out.str();
}

bool TestSameImages()
{
  bool ok = true;
  for (int culler = 0; culler < 3; ++culler)
  {
    Scene actors, instanced;
    Build(actors, false, culler);
    Build(instanced, true, culler);
    for (int view = 0; view < 3; ++view)
    {
      SetCamera(actors.Renderer, view);
      SetCamera(instanced.Renderer, view);
      actors.Window->Render();
      instanced.Window->Render();
      std::string why;
      const bool same = st::ImagesIdentical(
        st::CaptureImage(actors.Window), st::CaptureImage(instanced.Window), &why);
      std::ostringstream what;
      what << "culler " << culler << ", view " << view << ": the same image as 72 actors" << why;
      ok &= Check(same, what.str());
      ok &= Check(
        st::CoveredFraction(st::CaptureImage(instanced.Window)) > 0.05, "  and something is drawn");
      if (culler > 0)
      {
        // The cullers see the same boxes in the same order: the same placements survive.
        const std::set<vtkIdType> byActors = Kept(actors);
        const std::set<vtkIdType> byPlacements = Kept(instanced);
        ok &= Check(byActors == byPlacements,
          "  the same placements kept (" + std::to_string(byPlacements.size()) +
            " of 72): " + Ids(byPlacements) + "| actors: " + Ids(byActors));
        if (view == 1 && culler == 2)
        {
          auto* occlusion =
            vtkOcclusionCuller::SafeDownCast(instanced.Renderer->GetCullers()->GetItemAsObject(0));
          ok &= Check(occlusion->GetNumberOfPropsCulledByOcclusion() > 0,
            "  down a row, placements are culled by occlusion (" +
              std::to_string(occlusion->GetNumberOfPropsCulledByOcclusion()) + ")");
        }
      }
    }
  }
  return ok;
}

/// The actor's own matrix (here its position) applies after each placement's: the image of 72
/// actors whose user matrices are translation x placement; moving it refits the culler.
bool TestOwnTransform()
{
  bool ok = true;
  Scene actors, instanced;
  Build(actors, false, 2);
  Build(instanced, true, 2);
  SetCamera(actors.Renderer, 0);
  SetCamera(instanced.Renderer, 0);
  actors.Window->Render();
  instanced.Window->Render();
  const double move[16] = { 1, 0, 0, -2.5, 0, 1, 0, 1.0, 0, 0, 1, 0.5, 0, 0, 0, 1 };
  const std::vector<std::vector<double>> placements = Placements();
  for (std::size_t i = 0; i < actors.Actors.size(); ++i)
  {
    vtkNew<vtkMatrix4x4> matrix;
    vtkMatrix4x4::Multiply4x4(move, placements[i].data(), &matrix->Element[0][0]);
    actors.Actors[i]->SetUserMatrix(matrix);
  }
  instanced.Instanced->SetPosition(-2.5, 1.0, 0.5);
  actors.Window->Render();
  instanced.Window->Render();
  std::string why;
  ok &= Check(
    st::ImagesIdentical(st::CaptureImage(actors.Window), st::CaptureImage(instanced.Window), &why),
    "moved by its position: the same image as 72 actors moved alike" + why);
  ok &= Check(Kept(actors) == Kept(instanced), "  and the same placements kept");
  return ok;
}

/// Placements added or removed between frames are culled and drawn like the first ones.
bool TestPlacementsChange()
{
  bool ok = true;
  Scene scene;
  Build(scene, true, 2);
  SetCamera(scene.Renderer, 0);
  scene.Window->Render();
  vtkInstancedActor* actor = scene.Instanced;
  const double added[16] = { 1, 0, 0, 4, 0, 1, 0, 7, 0, 0, 1, 1, 0, 0, 0, 1 };
  actor->AddPlacement(added, 1000);
  scene.Window->Render();
  bool drawn = false;
  for (vtkIdType k = 0; k < actor->GetNumberOfVisiblePlacements(); ++k)
  {
    drawn = drawn || actor->GetPlacementId(actor->GetVisiblePlacement(k)) == 1000;
  }
  ok &= Check(drawn, "a placement added after the first frame is drawn");
  actor->RemoveAllPlacements();
  const double one[16] = { 1, 0, 0, 4, 0, 1, 0, 2, 0, 0, 1, 0, 0, 0, 0, 1 };
  actor->AddPlacement(one);
  scene.Window->Render();
  ok &= Check(actor->GetNumberOfVisiblePlacements() == 1 && actor->GetVisiblePlacement(0) == 0,
    "after RemoveAllPlacements and one AddPlacement: that one drawn");
  ok &= Check(st::CoveredFraction(st::CaptureImage(scene.Window)) > 0.001, "  and seen");
  actor->RemoveAllPlacements();
  scene.Window->Render();
  ok &= Check(st::CoveredFraction(st::CaptureImage(scene.Window)) == 0.0,
    "without placements nothing is drawn");
  return ok;
}

/// With SortingStyle, the visible placements of an instanced actor are drawn in depth order too
/// (front to back: each nearer one first, for the depth test; back to front: the reverse).
bool TestPlacementsInDepthOrder()
{
  bool ok = true;
  Scene scene;
  Build(scene, true, 1);
  auto* culler = vtkOctreeCuller::SafeDownCast(scene.Renderer->GetCullers()->GetItemAsObject(0));
  SetCamera(scene.Renderer, 0);
  vtkCamera* cam = scene.Renderer->GetActiveCamera();
  double eye[3], dop[3];
  cam->GetPosition(eye);
  cam->GetDirectionOfProjection(dop);
  auto depths = [&]()
  {
    std::vector<double> d;
    for (vtkIdType k = 0; k < scene.Instanced->GetNumberOfVisiblePlacements(); ++k)
    {
      double b[6];
      scene.Instanced->GetPlacementBounds(scene.Instanced->GetVisiblePlacement(k), b);
      d.push_back((0.5 * (b[0] + b[1]) - eye[0]) * dop[0] +
        (0.5 * (b[2] + b[3]) - eye[1]) * dop[1] + (0.5 * (b[4] + b[5]) - eye[2]) * dop[2]);
    }
    return d;
  };
  culler->SetSortingStyle(VTK_CULLER_SORT_FRONT_TO_BACK);
  scene.Window->Render();
  std::vector<double> d = depths();
  ok &= Check(d.size() > 10 && std::is_sorted(d.begin(), d.end()),
    "front to back: " + std::to_string(d.size()) + " visible placements, nearest first");
  culler->SetSortingStyle(VTK_CULLER_SORT_BACK_TO_FRONT);
  scene.Window->Render();
  d = depths();
  ok &= Check(d.size() > 10 && std::is_sorted(d.rbegin(), d.rend()), "back to front: farthest first");
  culler->SetSortingStyle(VTK_CULLER_SORT_NONE);
  scene.Window->Render();
  bool indexOrder = true;
  for (vtkIdType k = 1; k < scene.Instanced->GetNumberOfVisiblePlacements(); ++k)
  {
    indexOrder = indexOrder &&
      scene.Instanced->GetVisiblePlacement(k - 1) < scene.Instanced->GetVisiblePlacement(k);
  }
  ok &= Check(indexOrder, "no sorting: in placement order");
  return ok;
}

bool TestBadInput()
{
  bool ok = true;
  vtkNew<vtkInstancedActor> actor;
  double nan[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  nan[3] = std::numeric_limits<double>::quiet_NaN();
  ok &= Check(actor->AddPlacement(nan) == -1, "a NaN matrix is refused");
  double singular[16] = { 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  ok &= Check(actor->AddPlacement(singular) == -1, "a singular matrix is refused");
  ok &= Check(actor->AddPlacement(nullptr) == -1, "no matrix is refused");
  ok &= Check(actor->GetNumberOfPlacements() == 0, "  nothing was added");
  double bounds[6];
  ok &= Check(!actor->GetPlacementBounds(0, bounds) && actor->GetPlacementMatrix(5) == nullptr &&
      actor->GetPlacementId(-1) == -1,
    "queries out of range answer no");
  const double identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  ok &= Check(actor->AddPlacement(identity, 42) == 0 && actor->GetPlacementId(0) == 42,
    "a good matrix is added with its id");
  const vtkIdType indices[3] = { 0, 7, -1 };
  actor->SetVisiblePlacements(indices, 3);
  ok &= Check(actor->GetNumberOfVisiblePlacements() == 1 && actor->GetVisiblePlacement(0) == 0,
    "visible indices out of range are dropped");
  actor->SetAllPlacementsVisible();
  ok &= Check(actor->GetNumberOfVisiblePlacements() == 1, "all placements visible again");

  // Without a mapper, without placements, and with placements under a culler: no crash.
  Scene scene;
  Build(scene, true, 2);
  vtkNew<vtkInstancedActor> empty;
  vtkNew<vtkPolyDataMapper> mapper;
  vtkNew<vtkSphereSource> sphere;
  mapper->SetInputConnection(sphere->GetOutputPort());
  empty->SetMapper(mapper);
  scene.Renderer->AddActor(empty);
  scene.Renderer->AddActor(actor); // no mapper
  SetCamera(scene.Renderer, 0);
  scene.Window->Render();
  ok &= Check(st::CoveredFraction(st::CaptureImage(scene.Window)) > 0.05,
    "an actor without placements or without a mapper beside placed ones: drawn, no crash");
  std::ostringstream print;
  scene.Instanced->Print(print);
  ok &= Check(print.str().find("NumberOfPlacements: 72") != std::string::npos, "PrintSelf");
  return ok;
}
} // namespace

int TestInstancedActor(int, char*[])
{
  // The expected errors are judged through the output window; loguru's copy on stderr would
  // match ctest's "ERR|" failure pattern.
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  st::StrictVtkOutput vtkOutput;
  vtkOutput.ExpectError("a matrix with a NaN or infinite element");
  vtkOutput.ExpectError("a singular matrix");
  vtkOutput.ExpectError("indices out of");
  vtkOutput.ExpectWarning("non-finite bounds");
  bool ok = TestSameImages();
  ok &= TestPlacementsChange();
  ok &= TestPlacementsInDepthOrder();
  ok &= TestOwnTransform();
  ok &= TestBadInput();
  return vtkOutput.ExitCode(ok ? EXIT_SUCCESS : EXIT_FAILURE);
}
