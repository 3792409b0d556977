// The command line of scenevis: the options of its four commands, their parsing and the checks
// that make a bad command line a usage error (one line, exit 2), and the --help text.
#ifndef scenevis_tool_Options_h
#define scenevis_tool_Options_h

#include "CameraFile.h"

#include <vtkType.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace scenevis
{
namespace tool
{

/// A bad command line (or a scene or camera that contradicts it): exit code 2.
struct UsageError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

/// Everything the command line says; ParseOptions fills in the per-command defaults.
struct Options
{
  std::string command;
  std::string scene = "spheres";
  std::vector<std::string> scenes; ///< bench: every --scene, in order
  std::string outDir = ".";
  bool outDirSet = false;
  bool framesSet = false;
  bool sizeSet = false;
  bool orbitSet = false;
  bool trianglesSet = false;
  vtkIdType triangles = 20000;
  vtkIdType parts = 1000;
  double opacity = 0.4; ///< a model file's: only with --opacity (else its own materials')
  bool opacitySet = false;
  bool instances = false; ///< --instances: a glTF's meshes once each, one actor per placement
  /// --instance-actors: one vtkActor per placement (the path before vtkInstancedActor)
  bool instanceActors = false;
  /// --camera, --up, --parallel, --view-angle, --parallel-scale, --clipping-range.
  CameraSpec camera;
  /// --cameras FILE.json: one run per camera (the command line's camera options as defaults).
  std::string camerasFile;
  std::vector<CameraSpec> cameras;
  /// The integer cell arrays that name parts and rooms (--part-array, --room-array).
  std::string partArray = "PartId";
  std::string roomArray = "RoomId";
  bool partArraySet = false;
  bool roomArraySet = false;
  std::string sort = "auto";
  std::string cull = "auto";
  std::string portals;     ///< --portals FILE.vtp
  std::string exportScene; ///< cull --export-scene PREFIX
  bool exact = false;      ///< cull --exact: compare with the ID-buffer visible set
  /// portals --keep-leaking-rooms: rooms of a model that leaks (not conservative).
  bool keepLeakingRooms = false;
  /// --pvs-budget SECONDS: wall-clock budget of the PVS precompute of --cull pvs (0: none).
  double pvsBudget = 0.0;
  /// --chunk-size N: triangles per chunk of --cull chunked / chunked-occlusion (0: the mapper's
  /// default).
  int chunkSize = 0;
  /// --record-occlusion FILE: every cull of --cull occlusion or chunked-occlusion written to FILE,
  /// for scenevis_occlusion_replay (SetOcclusionRecordFile of the culler or chunked mapper).
  std::string recordOcclusion;
  int width = 800;
  int height = 600;
  int frames = 1;
  double orbit = 5.0;
  std::string out;
  std::string report;
  std::string backend;
  bool frontToBack = false;
};

/// The text of `scenevis --help`.
const char* HelpText();

/// The options of `scenevis COMMAND ...` (argv[1] is the command), checked together; reads the
/// --cameras file. Throws UsageError.
Options ParseOptions(int argc, char* argv[]);

/// What a --cull method name runs. Portals: portals, pvs, portals+occlusion, pvs+occlusion
/// (vtkPortalCuller first). Pvs: pvs, pvs+occlusion. Occlusion: occlusion, portals+occlusion,
/// pvs+occlusion (vtkOcclusionCuller, after the portal culler when there is one).
bool CullUsesPortals(const std::string& method);
bool CullUsesPvs(const std::string& method);
bool CullUsesOcclusion(const std::string& method);

/// The cameras a command runs: every camera of --cameras, else the command line's one.
std::vector<CameraSpec> CamerasToRun(const Options& options);

/// --backend: sets SCENEVIS_BACKEND, which the render windows made after this read.
void ApplyBackendOption(const Options& options);

} // namespace tool
} // namespace scenevis

#endif
