// TestSceneVisPluginMPI PLUGIN_FILE OUT_DIR [--reference DIR] [--engine FILE.glb] [--no-sort]:
// exact translucency across MPI ranks with ParaView's data-parallel engine, run as pvbatch runs
// (`mpiexec -n N`, a batch process module: rank 0 drives the server manager, the other ranks
// serve it), without Python (Debian's python3-paraview conflicts with python3-vtk9).
//
// Each scene (the 64 overlapping translucent spheres of "SceneVis Demo Scene", and with
// --engine the real 2CylinderEngine, opacity 0.4) is produced in pieces (the demo source gives
// each rank whole parts; the engine is read on rank 0 only) and drawn in
// three views: "SceneVis Ordered Translucency" (SortTranslucentGeometry on), ParaView's render
// view with 100 depth peels (the reference), and ParaView's render view as it comes (its
// default translucency). With more than one rank ParaView redistributes the translucent data
// into convex kd-tree regions, one per rank (cells split at the region boundaries), every rank's
// view orders its own region's polygons with the BSP, and IceT composites the ranks' images in
// the regions' visibility order: the image must be the one-rank image.
//
// The images (OUT_DIR/<scene>-<view>.png) and the fragments rank 0 sorted
// (OUT_DIR/<scene>-fragments.txt) are written. With --reference DIR (the output of a run on one
// rank) the SceneVis view's image must equal the reference (see the thresholds below), and rank
// 0 must have sorted fewer fragments than the one rank did (its region only: the data was
// distributed); ParaView's default translucency is measured beside it. --no-sort draws the
// SceneVis view in cell order (the mutation that the comparison must catch).
#include "vtkBSPTranslucentPass.h"
#include "vtkSceneVisRenderView.h"

#include "PluginTesting.h"
#include "RetryXOpenDisplay.h"

#include "vtkCompositeDataGeometryFilter.h"
#include "vtkGLTFReader.h"
#include "vtkImageData.h"
#include "vtkInitializationHelper.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPNGReader.h"
#include "vtkPNGWriter.h"
#include "vtkPVDataInformation.h"
#include "vtkPolyData.h"
#include "vtkProcessModule.h"
#include "vtkSMParaViewPipelineController.h"
#include "vtkSMPluginManager.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxyManager.h"
#include "vtkSMSession.h"
#include "vtkSMSessionProxyManager.h"
#include "vtkSMSourceProxy.h"
#include "vtkSMViewProxy.h"
#include "vtkSmartPointer.h"
#include "vtkXMLPolyDataWriter.h"

#include <vtksys/SystemTools.hxx>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

namespace
{
using scenevis_pvtest::Check;

constexpr int kImageSize = 240;

struct Options
{
  std::string plugin, out, reference, engine;
  bool sort = true;
};

vtkSmartPointer<vtkSMSourceProxy> NewSource(vtkSMSessionProxyManager* pxm,
  vtkSMParaViewPipelineController* controller, const char* group, const char* name)
{
  vtkSmartPointer<vtkSMSourceProxy> proxy;
  proxy.TakeReference(vtkSMSourceProxy::SafeDownCast(pxm->NewProxy(group, name)));
  if (proxy)
  {
    controller->InitializeProxy(proxy);
  }
  return proxy;
}

/// The camera the scene is seen with: its centre from a little above and to the side, far
/// enough for the whole of it.
scenevis_pvtest::ViewCamera CameraFor(const double bounds[6])
{
  scenevis_pvtest::ViewCamera camera{};
  double diagonal = 0.0;
  for (int i = 0; i < 3; ++i)
  {
    camera.focal[i] = 0.5 * (bounds[2 * i] + bounds[2 * i + 1]);
    diagonal += (bounds[2 * i + 1] - bounds[2 * i]) * (bounds[2 * i + 1] - bounds[2 * i]);
  }
  diagonal = std::sqrt(diagonal);
  const double direction[3] = { 0.15, 0.1, 1.0 };
  for (int i = 0; i < 3; ++i)
  {
    camera.eye[i] = camera.focal[i] + 1.5 * diagonal * direction[i];
  }
  return camera;
}

void WritePng(vtkImageData* image, const std::string& path)
{
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(path.c_str());
  writer->Write();
}

vtkSmartPointer<vtkImageData> ReadPng(const std::string& path)
{
  if (!std::ifstream(path))
  {
    return nullptr;
  }
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  return reader->GetOutput();
}

long long ReadCount(const std::string& path)
{
  std::ifstream in(path);
  long long count = -1;
  in >> count;
  return in ? count : -1;
}

/// One scene in the three views; the checks against the reference run when there is one.
void RenderScene(vtkSMSessionProxyManager* pxm, vtkSMParaViewPipelineController* controller,
  vtkSMSourceProxy* source, const double bounds[6], const std::string& scene,
  const Options& options, int ranks)
{
  const auto camera = CameraFor(bounds);
  auto sceneVis = scenevis_pvtest::NewView(
    pxm, controller, "SceneVisRenderView", camera, kImageSize, 0, options.sort);
  auto peeled = scenevis_pvtest::NewView(pxm, controller, "RenderView", camera, kImageSize, 100);
  auto paraviewDefault =
    scenevis_pvtest::NewView(pxm, controller, "RenderView", camera, kImageSize, -1);
  Check(sceneVis && peeled && paraviewDefault, scene + ": the three views exist");
  if (!sceneVis || !peeled || !paraviewDefault)
  {
    return;
  }
  const auto ordered = scenevis_pvtest::Render(sceneVis, source, kImageSize);
  const auto reference = scenevis_pvtest::Render(peeled, source, kImageSize);
  const auto asItComes = scenevis_pvtest::Render(paraviewDefault, source, kImageSize);
  auto* view = vtkSceneVisRenderView::SafeDownCast(sceneVis->GetClientSideObject());
  const long long fragments = view && options.sort
    ? static_cast<long long>(view->GetSortingPass()->GetNumberOfFragments())
    : -1;
  const std::string base = options.out + "/" + scene;
  WritePng(ordered, base + "-scenevis.png");
  WritePng(reference, base + "-peel100.png");
  WritePng(asItComes, base + "-default.png");
  std::ofstream(base + "-fragments.txt") << fragments << "\n";

  const auto orderedError = scenevis_pvtest::Compare(ordered, reference);
  const auto defaultError = scenevis_pvtest::Compare(asItComes, reference);
  std::cout << "      " << scene << ", " << ranks << " rank(s), " << kImageSize << "x" << kImageSize
            << ", opacity 0.4, against 100 depth peels on as many ranks: SceneVis "
            << scenevis_pvtest::Describe(orderedError) << "; ParaView's default "
            << scenevis_pvtest::Describe(defaultError) << "; rank 0 sorted " << fragments
            << " fragments\n";
  Check(orderedError.mean >= 0.0, scene + ": images rendered and read back");
  // On any number of ranks the view must look like ParaView's render view, anti-aliasing (FXAA,
  // on in ParaView's views) included. Measured: 0.06-0.68/255 and at most 5 pixels of 57,600;
  // one rank without FXAA in the SceneVis view: 0.104 % of the spheres' pixels, 0.911 % of the
  // engine's (their edges).
  Check(orderedError.mean >= 0.0 && orderedError.mean <= 1.0 && orderedError.offPercent <= 0.02,
    scene +
      ": the SceneVis image equals 100 depth peels on as many ranks within 1/255 mean and "
      "0.02 % of pixels");
  if (options.reference.empty())
  {
    return;
  }
  const std::string referenceBase = options.reference + "/" + scene;
  const auto oneRank = ReadPng(referenceBase + "-scenevis.png");
  const auto oneRankDefault = ReadPng(referenceBase + "-default.png");
  const long long oneRankFragments = ReadCount(referenceBase + "-fragments.txt");
  Check(oneRank != nullptr && oneRankFragments > 0,
    scene + ": the one-rank reference run's image and fragment count");
  if (!oneRank)
  {
    return;
  }
  const auto error = scenevis_pvtest::Compare(ordered, oneRank);
  const auto defaultAcross = scenevis_pvtest::Compare(asItComes, oneRankDefault);
  std::cout << "      " << scene << ", " << ranks << " ranks against 1 rank: SceneVis "
            << scenevis_pvtest::Describe(error) << "; ParaView's default "
            << scenevis_pvtest::Describe(defaultAcross)
            << "; fragments sorted by rank 0: " << fragments << " of " << oneRankFragments
            << " on one rank\n";
  // The issue's target is 0.5/255 and no pixel off by more than 16. Measured (BENCHMARKS "Exact
  // translucency on MPI ranks"): 0.05-0.19/255 and 0-3 pixels of 57,600 (the engine's). Drawing
  // in cell order (--no-sort) gives 5.0 % of the triangles' pixels, 13.5 % of the spheres', 12.8 %
  // of the engine's; the one-rank view without FXAA (before vtkOrderedTranslucentPass applied the
  // renderer's FXAA) 0.09 % of the spheres' and 0.89 % of the engine's.
  Check(error.mean >= 0.0 && error.mean <= 0.5 && error.offPercent <= 0.01,
    scene + ": the " + std::to_string(ranks) +
      "-rank SceneVis image equals the one-rank image within 0.5/255 mean and 0.01 % of pixels");
  // The three demo triangles are too few for ParaView's kd-tree to give both ranks some.
  if (ranks > 1 && oneRankFragments >= 1000)
  {
    Check(fragments > 0 && fragments < oneRankFragments,
      scene + ": rank 0 sorted only its own region (the data was distributed)");
  }
}

/// Demo scene @p sceneId of the plugin's source, generated in pieces: each rank makes its parts.
void RunDemoScene(vtkSMSessionProxyManager* pxm, vtkSMParaViewPipelineController* controller,
  int sceneId, const std::string& scene, const Options& options, int ranks)
{
  auto source = NewSource(pxm, controller, "sources", "SceneVisDemoScene");
  Check(source != nullptr, "the plugin's source SceneVisDemoScene exists");
  if (!source)
  {
    return;
  }
  vtkSMPropertyHelper(source, "Scene").Set(sceneId);
  source->UpdateVTKObjects();
  source->UpdatePipeline();
  // The bounds of every rank's piece together (rank 0's own piece is only part of the scene).
  double bounds[6];
  source->GetDataInformation(0)->GetBounds(bounds);
  RenderScene(pxm, controller, source, bounds, scene, options, ranks);
}

/// The engine read on rank 0 (ParaView's glTF reader would read it on every rank), merged into
/// one surface and written where ParaView's XML reader gives it to rank 0's piece.
void RunEngine(vtkSMSessionProxyManager* pxm, vtkSMParaViewPipelineController* controller,
  const Options& options, int ranks)
{
  vtkNew<vtkGLTFReader> reader;
  reader->SetFileName(options.engine.c_str());
  vtkNew<vtkCompositeDataGeometryFilter> merge;
  merge->SetInputConnection(reader->GetOutputPort());
  merge->Update();
  vtkPolyData* engine = merge->GetOutput();
  Check(engine->GetNumberOfPolys() > 100000,
    "the 2CylinderEngine read (" + std::to_string(engine->GetNumberOfPolys()) + " polygons)");
  const std::string file = options.out + "/engine.vtp";
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(engine);
  writer->SetFileName(file.c_str());
  writer->Write();
  auto source = NewSource(pxm, controller, "sources", "XMLPolyDataReader");
  vtkSMPropertyHelper(source, "FileName").Set(file.c_str());
  source->UpdateVTKObjects();
  source->UpdatePipeline();
  double bounds[6];
  engine->GetBounds(bounds);
  RenderScene(pxm, controller, source, bounds, "engine", options, ranks);
}

bool ParseOptions(int argc, char* argv[], Options& options)
{
  if (argc < 3)
  {
    return false;
  }
  options.plugin = argv[1];
  options.out = argv[2];
  for (int i = 3; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--reference" && i + 1 < argc)
    {
      options.reference = argv[++i];
    }
    else if (arg == "--engine" && i + 1 < argc)
    {
      options.engine = argv[++i];
    }
    else if (arg == "--no-sort")
    {
      options.sort = false;
    }
    else
    {
      return false;
    }
  }
  return true;
}
} // namespace

int main(int argc, char* argv[])
{
  Options options;
  if (!ParseOptions(argc, argv, options))
  {
    std::cerr << "usage: TestSceneVisPluginMPI PLUGIN_FILE OUT_DIR [--reference DIR] "
                 "[--engine FILE.glb] [--no-sort]\n";
    return EXIT_FAILURE;
  }
  vtkInitializationHelper::Initialize(argc, argv, vtkProcessModule::PROCESS_BATCH);
  vtkProcessModule* processModule = vtkProcessModule::GetProcessModule();
  const int ranks = processModule->GetNumberOfLocalPartitions();
  if (processModule->GetPartitionId() > 0)
  {
    // A satellite: serves rank 0's server manager until it closes the session (pvbatch).
    const vtkIdType id = vtkSMSession::ConnectToSelf();
    processModule->GetGlobalController()->ProcessRMIs();
    processModule->UnRegisterSession(id);
    vtkInitializationHelper::Finalize();
    return EXIT_SUCCESS;
  }
  {
    Check(scenevis_pvtest::XOpenDisplayRetries(), "XOpenDisplay tries again when Xvfb hangs up");
    Check(vtksys::SystemTools::MakeDirectory(options.out).IsSuccess(),
      "the output directory " + options.out);
    const vtkIdType id = vtkSMSession::ConnectToSelf();
    auto* session = vtkSMSession::SafeDownCast(processModule->GetSession(id));
    vtkNew<vtkSMParaViewPipelineController> controller;
    Check(session && controller->InitializeSession(session),
      "a batch ParaView session on " + std::to_string(ranks) + " rank(s)");
    const bool loaded = session &&
      vtkSMProxyManager::GetProxyManager()->GetPluginManager()->LoadRemotePlugin(
        options.plugin.c_str(), session);
    Check(loaded, "LoadPlugin " + options.plugin + " on every rank");
    if (loaded)
    {
      vtkSMSessionProxyManager* pxm = session->GetSessionProxyManager();
      RunDemoScene(pxm, controller, 2, "triangles", options, ranks); // interpenetrating
      RunDemoScene(pxm, controller, 0, "spheres", options, ranks);   // 4 x 4 x 4, overlapping
      if (!options.engine.empty())
      {
        RunEngine(pxm, controller, options, ranks);
      }
      else
      {
        std::cout << "skip: the engine (no --engine FILE: the real models were not fetched)\n";
      }
    }
    processModule->UnRegisterSession(id);
  }
  vtkInitializationHelper::Finalize();
  const int failures = scenevis_pvtest::Failures();
  std::cout << (failures ? "FAILED: " : "passed: ") << failures << " failed checks\n";
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
