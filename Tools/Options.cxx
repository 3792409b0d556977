// The command line of scenevis: parsing, checks, --help.
#include "Options.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace scenevis
{
namespace tool
{
namespace
{
const char* const kHelp = R"(scenevis - exact translucency order and culling of VTK scenes, headless

Usage:
  scenevis render [options]   render offscreen to PNG, print (and optionally write) a report
  scenevis sort [options]     write the polydata sorted for a camera (VTK XML .vtp) with
                              OriginalCellId and SortRank cell arrays
  scenevis cull [options]     print as JSON what a culling mode keeps for a camera: visible
                              props, parts, rooms, chunks and triangles
  scenevis bench [options]    accuracy versus time of every translucency method: a CSV table
                              and a plot (PNG) of frame time against image error
  scenevis portals --out OUT [options]  rooms and portals found from the scene's geometry
                              (walls, floors, ceilings; doors and windows are holes in them):
                              OUT.vtp (the scene with a room cell array, --room-array, -1
                              outside) and OUT-portals.vtp (RoomA, RoomB) for --portals;
                              translucent cells (glass) do not close an opening. Prints
                              what was found as JSON (rooms, portals, leaks, seconds)
  scenevis --help | --version

Scene (all commands):
  --scene NAME|KEY|FILE embedded demo: spheres (default: 64 overlapping translucent spheres),
                        cyclic-quads, triangles, cad, building; or a key of the data cache
                        (scripts/fetch-data.sh), e.g. bunny-stl; or a model file
                        (.vtp .vtk .ply .stl .obj .glb .gltf .wrl; glTF and VRML parts
                        become PartId parts with their own colours). bench: repeatable
  --portals FILE.vtp    portals of a model file: one polygon per portal with integer cell
                        arrays RoomA and RoomB; the model needs a room cell array (RoomId
                        or --room-array; -1 = outside). The building demo brings its own
                        portals
  --instances           render, cull, sort: a glTF (.glb .gltf) or VRML (.wrl) file as
                        instances: each distinct mesh loaded once with one mapper, one
                        actor (user matrix) per glTF node or VRML shape that draws it (a
                        USE of a DEF'd Shape or geometry), not one flattened copy each.
                        Culling modes that cull props (and none); render's sort none, oit,
                        multi-actor or peel:N. cull: a placement is a part (its index, the
                        flattened file's PartId); --exact renders the placements flattened.
                        sort: the placements flattened into world space, then the BSP
                        (exact; the flattened file's polygons in the same order).
                        Each mesh is one vtkInstancedActor drawing its placements, culled
                        placement by placement (--cull none, octree, occlusion, auto
                        choosing one of them; render's sort none, oit or peel:N)
  --instance-actors     with --instances: one vtkActor per placement instead (about 4.6 kB
                        each); always so for multi-actor sorting, frustum (VTK's culler of
                        props) and normal-cones
  --triangles N         approximate triangle count of the spheres/cad demos (default 20000)
  --parts N             parts of the cad demo (default 1000)
  --opacity A           opacity given to every cell of a model file, in (0, 1] (default: the
                        file's own: the materials of glTF/VRML parts or a Colors RGBA cell
                        array, else opaque). The demo scenes keep their own (translucent
                        and opaque parts): --opacity with one warns that it is ignored
  --part-array NAME     render, cull, bench: the integer cell array naming parts (default
                        PartId); one value per cell, at most 1,000,000 distinct values
  --room-array NAME     render, cull, bench: the integer cell array naming rooms, -1 = outside
                        (default RoomId)

Camera (render, sort, cull; bench: one orbit from it):
  --camera EX,EY,EZ[,FX,FY,FZ]   eye (and focal point; default: the scene's centre);
                        default camera: a three-quarter view that fits the scene
  --up X,Y,Z            camera view-up (default: +z for the cad and building demos, else +y)
  --parallel            parallel projection (scale fitted to the scene)
  --parallel-scale S    parallel projection with half-height S in world units (> 0);
                        implies --parallel
  --view-angle DEG      perspective view angle in degrees, in (0, 180) (default 30; the
                        default camera moves to fit the scene into it)
  --clipping-range NEAR,FAR  fixed near and far distances, 0 < NEAR < FAR (default: fitted
                        to the visible props after every camera move)
  --cameras FILE.json   run once per camera of FILE: a JSON array of objects
                        {"eye": [x,y,z], "focal": [x,y,z], "up": [x,y,z],
                        "view_angle": DEG or "parallel_scale": S, "clipping_range": [n,f]};
                        eye and focal are required, the rest default to the options above.
                        render writes OUT-i.png and one frame per camera in the report, sort
                        writes OUT-i.vtp, cull prints a JSON array of one result per camera.
                        Not with --camera, --frames or --orbit

render and cull:
  --cull MODE           auto (default), none, frustum (VTK's vtkFrustumCoverageCuller),
                        octree (vtkOctreeCuller: BVH frustum culling), normal-cones (octree +
                        normal-cone back-face culling; actors drawn with back-face culling),
                        small:N (octree + small-feature culling below N pixels: APPROXIMATE),
                        occlusion (vtkOcclusionCuller: octree + conservative software
                        occlusion culling: what is hidden behind opaque parts is not drawn),
                        chunked (one mesh through vtkChunkedPolyDataMapper: chunks culled
                        inside it), chunked-occlusion (chunked + chunks hidden behind nearer
                        chunks culled, conservative; opaque), portals (vtkPortalCuller, exact frustum narrowing), pvs
                        (vtkPortalCuller with precomputed potentially visible sets),
                        portals+occlusion and pvs+occlusion (the portal culler, then
                        vtkOcclusionCuller on the props it kept: the parts of rooms seen through
                        portals that nearer parts hide are not drawn; give parts below rooms
                        with --part-array).
                        Prop culling modes draw one actor per part (--part-array, and room
                        where present); with those, --sort takes none, oit, multi-actor or
                        peel:N.
                        auto: rooms and portals -> portals; 100+ opaque parts of under 16
                        triangles on average (a game level's surfaces) -> one mesh: none, or
                        chunked-occlusion in chunks of 64 from 10,000 triangles; 100+ parts, at
                        most 25 % translucent, under 90 % of the triangles in the first view (with
                        --instances: 100+ placements, any view) -> octree, or occlusion when
                        the opaque parts' screen rectangles cover the area they span 4+ times;
                        an opaque mesh of 500k+ triangles -> chunked (with --instances:
                        octree, placements are not one mesh); otherwise none. The
                        report says why, in numbers. A frame whose camera did not move
                        re-uses the last visible set and order
  --pvs-budget SECONDS  with --cull pvs (or pvs+occlusion): the PVS precompute's portal flow
                        shares SECONDS (wall clock, > 0; default: none) among the portals; a
                        portal's flow that used its share closes with what it might still see
                        (conservative, larger sets), and the report says how many
                        (culling.portals.pvs.degraded_portals, budget_exceeded)
  --chunk-size N        with --cull chunked or chunked-occlusion (or auto when it picks them):
                        at most N triangles per chunk (default 2048; the chunks' tree is
                        built once)
  --record-occlusion FILE  with --cull occlusion, chunked-occlusion, portals+occlusion or
                        pvs+occlusion: every cull's occluder rasterization (buffer size, camera,
                        each occluder's triangles) written to FILE, for
                        scenevis_occlusion_replay FILE (times the rasterizer alone)

render:
  --sort METHOD         auto (default), none (unsorted alpha), oit (VTK's default weighted
                        OIT), depth-sort (vtkDepthSortPolyData), painter (vtkPainterSortFilter:
                        Newell's painter's algorithm with splits, redone every frame),
                        bsp (vtkBSPSortFilter), bsp-leaves:N (vtkBSPSortFilter with ordered
                        leaves of up to N polygons, 1-256: fewer fragments, more order time),
                        bsp-mapper (vtkBSPSortedPolyDataMapper: the BSP
                        order rewritten into the index buffer only), multi-actor (one actor per
                        part (--part-array), ordered across actors by vtkBSPTranslucentPass),
                        peel:N (dual depth peeling, at most N peels)
  --size WxH            image size in pixels (default 800x600)
  --frames N            orbit frames (default 1); frame i is written as OUT-000i.png
  --orbit DEG           camera azimuth step per frame (default 5)
  --out FILE.png        output image (default scenevis.png)
  --report FILE.json    also write the report as JSON
  --backend osmesa|x11  rendering back-end (default osmesa, or $SCENEVIS_BACKEND)

cull:
  --size WxH            viewport whose aspect the camera uses (default 800x600)
  --report FILE.json    also write the JSON to a file
  --export-scene PREFIX write the scene as PREFIX.vtp (with its PartId/RoomId cell arrays) and
                        its portals as PREFIX-portals.vtp: the portal scene format
  --exact               also render the exact visible set (ID buffer, depth-tested, every
                        surface opaque) and report the cells and props the mode culled
                        although visible (false negatives) and drew although hidden

portals:
  --keep-leaking-rooms  write the rooms and portals of a model that leaks (by default it gets
                        none: every cell -1, no portal, since no room labelling of a leaking
                        model is conservative); NOT conservative: they may hide visible cells

sort:
  --out FILE.vtp        output polydata (required)
  --front-to-back       front-to-back instead of back-to-front

bench:
  Runs every method (none, oit, depth-sort, painter (skipped above 20000 triangles), bsp,
  bsp-mapper, multi-actor (scenes with parts), peel:4, peel:100 = the reference) on each scene
  in one process: a warm-up frame, then N frames on an orbit. Per method: the median frame time
  (sort + render), the median sort time, the image error against peel:100 at the same camera
  (mean absolute error in 0..255 levels, % of covered pixels off by more than 16 levels) and,
  where the method has a drawing order, the misordered pixels of the ID-buffer oracle (painter's
  ID image of the drawn fragments versus their z-buffer ID image; outside the edge mask, the
  pixels compared, and over all pixels), means over the frames.
  --scene ...           default: spheres (--triangles, default here 19000: 19456 triangles),
                        cyclic-quads, and bunny-stl if fetched
  --frames N            timed frames per method (default 10)
  --orbit DEG           azimuth step per frame (default 2)
  --size WxH            image size (default 640x480)
  --out-dir DIR         where accuracy-vs-time.csv and accuracy-vs-time.png go (default .)

A progress bar (BSP build, PVS precompute, frames) is drawn on stderr when it is a terminal.
The render report and cull's JSON give the camera used (position, focal_point, view_up,
parallel, view_angle, parallel_scale, clipping_range, clipping_range_fixed).
Exit codes: 0 success, 1 failure (unreadable or invalid file, e.g. a camera file or a part
array; rendering failed), 2 bad usage. Errors are one line on stderr.
)";

double ParseNumber(const std::string& flag, const std::string& text)
{
  try
  {
    std::size_t used = 0;
    const double value = std::stod(text, &used);
    if (used != text.size() || !std::isfinite(value))
    {
      throw std::invalid_argument(text);
    }
    return value;
  }
  catch (const std::exception&)
  {
    throw UsageError(flag + " expects a finite number, got '" + text + "'");
  }
}

long ParseCount(const std::string& flag, const std::string& text, long lo, long hi)
{
  const double value = ParseNumber(flag, text);
  if (value != std::floor(value) || value < lo || value > hi)
  {
    throw UsageError(flag + " expects a whole number from " + std::to_string(lo) + " to " +
      std::to_string(hi) + ", got '" + text + "'");
  }
  return static_cast<long>(value);
}

std::vector<double> ParseList(const std::string& flag, const std::string& text)
{
  std::vector<double> values;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ','))
  {
    values.push_back(ParseNumber(flag, item));
  }
  return values;
}

/// The camera options together: conflicts are usage errors; --cameras is read here, before
/// anything is loaded or written.
void CheckCameraOptions(Options& options)
{
  const CameraSpec& camera = options.camera;
  if (camera.viewAngle > 0.0 && camera.parallel)
  {
    throw UsageError("--view-angle is for perspective projection; with --parallel, "
                     "--parallel-scale sets the view's size");
  }
  if (options.camerasFile.empty())
    return;
  if (options.command == "bench")
    throw UsageError("--cameras belongs to render, sort and cull (bench orbits its own camera)");
  if (camera.hasEye)
    throw UsageError("--cameras and --camera both give the eye: use one of them");
  if (options.framesSet || options.orbitSet)
  {
    throw UsageError(std::string(options.framesSet ? "--frames" : "--orbit") +
      " orbits one camera; with --cameras, every camera of the file is one frame");
  }
  options.cameras = ReadCameraFile(options.camerasFile, camera);
}

} // namespace

const char* HelpText()
{
  return kHelp;
}

bool CullUsesPortals(const std::string& method)
{
  return method == "portals" || method == "portals+occlusion" || CullUsesPvs(method);
}

bool CullUsesPvs(const std::string& method)
{
  return method == "pvs" || method == "pvs+occlusion";
}

bool CullUsesOcclusion(const std::string& method)
{
  return method == "occlusion" || method == "portals+occlusion" || method == "pvs+occlusion";
}

Options ParseOptions(int argc, char* argv[])
{
  Options options;
  if (argc < 2)
  {
    throw UsageError("missing command (render, sort, cull, portals or bench); see scenevis --help");
  }
  options.command = argv[1];
  if (options.command != "render" && options.command != "sort" && options.command != "bench" &&
    options.command != "cull" && options.command != "portals")
  {
    throw UsageError("unknown command '" + options.command + "'; see scenevis --help");
  }
  for (int i = 2; i < argc; ++i)
  {
    const std::string flag = argv[i];
    auto value = [&]() -> std::string
    {
      if (i + 1 >= argc)
      {
        throw UsageError(flag + " needs a value");
      }
      return argv[++i];
    };
    if (flag == "--scene")
    {
      options.scene = value();
      options.scenes.push_back(options.scene);
    }
    else if (flag == "--triangles")
    {
      options.triangles = ParseCount(flag, value(), 64, 200000000);
      options.trianglesSet = true;
    }
    else if (flag == "--parts")
      options.parts = ParseCount(flag, value(), 1, 10000000);
    else if (flag == "--instances")
      options.instances = true;
    else if (flag == "--instance-actors")
      options.instanceActors = true;
    else if (flag == "--opacity")
    {
      options.opacity = ParseNumber(flag, value());
      options.opacitySet = true;
      if (options.opacity <= 0.0 || options.opacity > 1.0)
        throw UsageError("--opacity expects a value in (0, 1]");
    }
    else if (flag == "--camera")
    {
      const std::vector<double> v = ParseList(flag, value());
      if (v.size() != 3 && v.size() != 6)
        throw UsageError("--camera expects EX,EY,EZ or EX,EY,EZ,FX,FY,FZ");
      std::copy_n(v.begin(), 3, options.camera.eye);
      options.camera.hasEye = true;
      if (v.size() == 6)
      {
        std::copy_n(v.begin() + 3, 3, options.camera.focal);
        options.camera.hasFocal = true;
        if (std::equal(v.begin(), v.begin() + 3, v.begin() + 3))
          throw UsageError("--camera: the eye equals the focal point (no view direction)");
      }
    }
    else if (flag == "--cameras")
      options.camerasFile = value();
    else if (flag == "--parallel")
      options.camera.parallel = true;
    else if (flag == "--parallel-scale")
    {
      const std::string text = value();
      options.camera.parallelScale = ParseNumber(flag, text);
      const std::string problem = CheckParallelScale(options.camera.parallelScale);
      if (!problem.empty())
        throw UsageError(flag + " " + problem);
      options.camera.parallel = true; // a parallel scale only means something in parallel
    }
    else if (flag == "--view-angle")
    {
      options.camera.viewAngle = ParseNumber(flag, value());
      const std::string problem = CheckViewAngle(options.camera.viewAngle);
      if (!problem.empty())
        throw UsageError(flag + " " + problem);
    }
    else if (flag == "--clipping-range")
    {
      const std::string text = value();
      const std::vector<double> v = ParseList(flag, text);
      if (v.size() != 2)
        throw UsageError(flag + " expects NEAR,FAR, got '" + text + "'");
      const std::string problem = CheckClippingRange(v[0], v[1]);
      if (!problem.empty())
        throw UsageError(flag + " " + problem);
      std::copy_n(v.begin(), 2, options.camera.clippingRange);
    }
    else if (flag == "--up")
    {
      const std::vector<double> v = ParseList(flag, value());
      if (v.size() != 3 || (v[0] == 0.0 && v[1] == 0.0 && v[2] == 0.0))
        throw UsageError("--up expects a non-zero vector X,Y,Z");
      std::copy_n(v.begin(), 3, options.camera.up);
      options.camera.hasUp = true;
    }
    else if (flag == "--part-array" || flag == "--room-array")
    {
      const std::string name = value();
      if (name.empty())
        throw UsageError(flag + " expects the name of an integer cell array");
      (flag == "--part-array" ? options.partArray : options.roomArray) = name;
      (flag == "--part-array" ? options.partArraySet : options.roomArraySet) = true;
    }
    else if (flag == "--cull")
      options.cull = value();
    else if (flag == "--portals")
      options.portals = value();
    else if (flag == "--export-scene")
      options.exportScene = value();
    else if (flag == "--exact")
      options.exact = true;
    else if (flag == "--keep-leaking-rooms")
      options.keepLeakingRooms = true;
    else if (flag == "--pvs-budget")
    {
      const std::string text = value();
      options.pvsBudget = ParseNumber(flag, text);
      if (!(options.pvsBudget > 0.0) || options.pvsBudget > 1e6)
        throw UsageError(flag + " expects seconds in (0, 1000000], got '" + text + "'");
    }
    else if (flag == "--chunk-size")
      options.chunkSize = ParseCount(flag, value(), 1, 1 << 24);
    else if (flag == "--record-occlusion")
    {
      options.recordOcclusion = value();
      if (options.recordOcclusion.empty())
        throw UsageError("--record-occlusion expects a file name");
    }
    else if (flag == "--sort")
      options.sort = value();
    else if (flag == "--size")
    {
      const std::string size = value();
      const auto x = size.find('x');
      if (x == std::string::npos)
        throw UsageError("--size expects WxH, e.g. 800x600");
      options.width = static_cast<int>(ParseCount(flag, size.substr(0, x), 16, 8192));
      options.height = static_cast<int>(ParseCount(flag, size.substr(x + 1), 16, 8192));
      options.sizeSet = true;
    }
    else if (flag == "--frames")
    {
      options.frames = static_cast<int>(ParseCount(flag, value(), 1, 100000));
      options.framesSet = true;
    }
    else if (flag == "--orbit")
    {
      options.orbit = ParseNumber(flag, value());
      options.orbitSet = true;
    }
    else if (flag == "--out-dir")
    {
      options.outDir = value();
      options.outDirSet = true;
    }
    else if (flag == "--out")
      options.out = value();
    else if (flag == "--report")
      options.report = value();
    else if (flag == "--backend")
      options.backend = value();
    else if (flag == "--front-to-back")
      options.frontToBack = true;
    else
      throw UsageError("unknown option '" + flag + "'; see scenevis --help");
  }
  const std::string& s = options.sort;
  if (s != "auto" && s != "none" && s != "oit" && s != "depth-sort" && s != "painter" &&
    s != "bsp" && s.rfind("bsp-leaves:", 0) != 0 && s != "bsp-mapper" && s != "multi-actor" &&
    s.rfind("peel:", 0) != 0)
  {
    throw UsageError("--sort expects auto, none, oit, depth-sort, painter, bsp, bsp-leaves:N, "
                     "bsp-mapper, multi-actor or peel:N");
  }
  if (s.rfind("peel:", 0) == 0)
  {
    ParseCount("--sort peel:N", s.substr(5), 1, 10000);
  }
  if (s.rfind("bsp-leaves:", 0) == 0)
  {
    ParseCount("--sort bsp-leaves:N", s.substr(11), 1, 256);
  }
  const std::string& c = options.cull;
  if (c != "auto" && c != "none" && c != "frustum" && c != "octree" && c != "normal-cones" &&
    c != "chunked" && c != "chunked-occlusion" && !CullUsesPortals(c) && !CullUsesOcclusion(c) &&
    c.rfind("small:", 0) != 0)
  {
    throw UsageError(
      "--cull expects auto, none, frustum, octree, normal-cones, occlusion, small:N, "
      "chunked, chunked-occlusion, portals, pvs, portals+occlusion or pvs+occlusion, got '" +
      c + "'");
  }
  if (c.rfind("small:", 0) == 0)
  {
    const double pixels = ParseNumber("--cull small:N", c.substr(6));
    if (pixels <= 0.0 || pixels > 10000.0)
      throw UsageError(
        "--cull small:N expects a size in pixels in (0, 10000], got '" + c.substr(6) + "'");
  }
  if (options.pvsBudget > 0.0 && !CullUsesPvs(c))
  {
    throw UsageError(
      "--pvs-budget is the budget of --cull pvs's precompute (got --cull " + c + ")");
  }
  if (options.chunkSize > 0 && c != "chunked" && c != "chunked-occlusion" && c != "auto")
  {
    throw UsageError("--chunk-size sets the chunks of --cull chunked or chunked-occlusion (got "
                     "--cull " +
      c + ")");
  }
  if (!options.recordOcclusion.empty() &&
    ((!CullUsesOcclusion(c) && c != "chunked-occlusion") ||
      (options.command != "render" && options.command != "cull")))
  {
    throw UsageError("--record-occlusion records the culls of render or cull with --cull "
                     "occlusion, chunked-occlusion or portals/pvs+occlusion (got " +
      options.command + " --cull " + c + ")");
  }
  if ((!options.exportScene.empty() || options.exact) && options.command != "cull")
  {
    throw UsageError(
      std::string(options.exact ? "--exact" : "--export-scene") + " belongs to the cull command");
  }
  if (options.outDirSet && options.command != "bench")
  {
    throw UsageError("--out-dir belongs to the bench command (render writes its frames with "
                     "--out PREFIX)");
  }
  if (options.keepLeakingRooms && options.command != "portals")
  {
    throw UsageError("--keep-leaking-rooms belongs to the portals command");
  }
  if (options.command == "sort" && options.out.empty())
  {
    throw UsageError("sort needs --out FILE.vtp");
  }
  if (options.command == "portals" && options.out.empty())
  {
    throw UsageError("portals needs --out PREFIX (writes PREFIX.vtp and PREFIX-portals.vtp)");
  }
  if (options.command == "portals" && (options.instances || !options.portals.empty()))
  {
    throw UsageError(std::string(options.instances ? "--instances" : "--portals") +
      " does not go with portals, which finds the portals of one flattened model");
  }
  CheckCameraOptions(options);
  if ((options.partArraySet || options.roomArraySet) && options.command == "sort")
  {
    // The BSP order is one over all polygons: sort never splits the scene into parts or rooms.
    throw UsageError(std::string(options.partArraySet ? "--part-array" : "--room-array") +
      " belongs to render, cull and bench (sort orders all polygons as one)");
  }
  if (options.out.empty())
  {
    options.out = "scenevis.png";
  }
  if (options.instances && options.command == "bench")
    throw UsageError("--instances belongs to render, cull and sort");
  if (options.instanceActors && !options.instances)
    throw UsageError("--instance-actors goes with --instances");
  if (options.command == "bench")
  {
    if (!options.framesSet)
      options.frames = 10;
    if (!options.orbitSet)
      options.orbit = 2.0;
    if (!options.trianglesSet)
      options.triangles = 19000; // 19,456 spheres triangles: small enough for the painter
    if (!options.sizeSet)
    {
      options.width = 640;
      options.height = 480;
    }
  }
  return options;
}

std::vector<CameraSpec> CamerasToRun(const Options& options)
{
  return options.cameras.empty() ? std::vector<CameraSpec>{ options.camera } : options.cameras;
}

void ApplyBackendOption(const Options& options)
{
  if (!options.backend.empty())
  {
    setenv("SCENEVIS_BACKEND", options.backend.c_str(), 1);
  }
}

} // namespace tool
} // namespace scenevis
