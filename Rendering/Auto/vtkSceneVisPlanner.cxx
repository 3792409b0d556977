#include "vtkSceneVisPlanner.h"

#include "vtkActor.h"
#include "vtkAutoRooms.h"
#include "vtkBSPSortedPolyDataMapper.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkCuller.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkPropCollection.h"
#include "vtkRenderPass.h"
#include "vtkRenderer.h"
#include "vtkScenePlanInstaller.h"
#include "vtkScenePlanInventory.h"
#include "vtkScenePlanRooms.h"
#include "vtkSmartPointer.h"
#include "vtkWeakPointer.h"

#include <chrono>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkSceneVisPlanner);

namespace
{
/// Everything the visible set depends on apart from the props: camera and viewport.
void ViewKey(vtkRenderer* ren, std::vector<double>& key)
{
  key.clear();
  vtkCamera* camera = ren->GetActiveCamera();
  auto add = [&key](const double* v, int n) { key.insert(key.end(), v, v + n); };
  add(camera->GetPosition(), 3);
  add(camera->GetFocalPoint(), 3);
  add(camera->GetViewUp(), 3);
  add(camera->GetWindowCenter(), 2);
  key.push_back(camera->GetViewAngle());
  key.push_back(camera->GetParallelScale());
  key.push_back(camera->GetParallelProjection());
  key.push_back(vtkScenePlanInventory::AspectOf(ren));
  const int* size = ren->GetSize();
  key.push_back(size[0]);
  key.push_back(size[1]);
}
} // namespace

/// The renderer's StartEvent and DeleteEvent observer; owns the planner when it was made by
/// Attach().
class vtkSceneVisPlannerStart : public vtkCommand
{
public:
  static vtkSceneVisPlannerStart* New() { return new vtkSceneVisPlannerStart; }
  vtkTypeMacro(vtkSceneVisPlannerStart, vtkCommand);
  void Execute(vtkObject*, unsigned long event, void*) override
  {
    if (!this->Planner)
      return;
    if (event == vtkCommand::DeleteEvent)
      this->Planner->RendererDeleted();
    else
      this->Planner->Plan();
  }
  vtkSceneVisPlanner* Planner = nullptr;
  vtkSmartPointer<vtkSceneVisPlanner> Owned;
};

/// The plan and when it was made; the scene's facts are the inventory's, what is installed the
/// installer's.
class vtkSceneVisPlanner::vtkInternals
{
public:
  explicit vtkInternals(vtkSceneVisPlanner* self)
    : Self(self)
    , Inventory(self, [this](vtkActor* actor) { return this->Installer.ApplicationMapper(actor); })
    , Installer(self)
  {
  }

  vtkSceneVisPlanner* Self;
  vtkWeakPointer<vtkRenderer> Renderer;
  unsigned long StartTag = 0;
  unsigned long DeleteTag = 0;
  /// Weak: the renderer owns it (and through it, after Attach(), this planner).
  vtkWeakPointer<vtkSceneVisPlannerStart> StartCommand;
  vtkScenePlanInventory Inventory;
  vtkScenePlanInstaller Installer;
  vtkSmartPointer<vtkPolyData> Portals;
  std::string RoomIdArrayName = "RoomId";
  bool PortalsChanged = false;
  /// Rooms and portals generated when the application gives none (SetGenerateRooms).
  vtkScenePlanRooms Rooms;
  bool RoomsSettingChanged = false;
  /// The generated rooms' reason the culling reason quotes (it may move on under the same plan).
  std::string RoomsReasonShown;
  /// The facts line of the plan in force (those it was adopted on).
  std::string AdoptedFacts;
  vtkMTimeType PortalsTime = 0;

  // --- change detection ---
  vtkMTimeType PropsTime = 0;
  vtkMTimeType CameraTime = 0;
  vtkCamera* Camera = nullptr;
  int Size[2] = { -1, -1 };
  std::vector<double> View, NewView;

  // --- the plan ---
  bool Planned = false;
  vtkScenePlanChoice Cull{ "none", "not planned yet" };
  vtkScenePlanChoice Translucency{ "none", "not planned yet" };
  std::string CullReasonText = "not planned yet";
  std::string ReasonText = "not planned yet";
  std::string Pending; ///< a view-driven culling method waiting for SwitchFrames renders
  /// The facts of the scene itself (not of the view) at the last decision: when they change the
  /// plan follows at once, otherwise (the view, or props moved) only with hysteresis.
  std::vector<double> SceneKey;
  int PendingFrames = 0;
  bool WarnedEmpty = false;

  void Install(vtkRenderer* ren)
  {
    this->Installer.Install(ren, this->Cull.Method, this->Translucency.Method, this->Inventory,
      this->Self->ChunkedMinimumTriangles);
  }
  void UndoAll(vtkRenderer* ren);
  /// The portals the plan works with: the application's, else generated ones (or none).
  void UsePortals()
  {
    vtkPolyData* portals = this->Portals ? this->Portals.Get() : this->Rooms.GetPortals();
    const char* roomArray = this->Portals ? this->RoomIdArrayName.c_str() : "RoomId";
    this->Inventory.SetPortals(portals);
    this->Installer.SetPortals(portals, roomArray);
    this->Installer.SetCellRooms(
      this->Portals ? vtkScenePlanRooms::CellRooms() : this->Rooms.GetCellRooms());
  }
  void Adopt(const vtkScenePlanChoice& cull, const vtkScenePlanChoice& translucency);
  /// The reason texts of the plan in force: its facts and the generated rooms' latest reason.
  void ComposeReason();
  /// The translucency method for the culling method @p cull.
  vtkScenePlanChoice ChooseTranslucency(const vtkScenePlanChoice& cull);
};

void vtkSceneVisPlanner::vtkInternals::UndoAll(vtkRenderer* ren)
{
  this->Installer.Uninstall(ren);
  this->Installer.SetCellRooms({});
  this->Inventory.Clear();
  this->Rooms.Clear();
  this->Cull = { "none", "not planned yet" };
  this->Translucency = { "none", "not planned yet" };
  this->CullReasonText = this->ReasonText = "not planned yet";
  this->Planned = false;
  this->RoomsReasonShown.clear();
  this->Pending.clear();
  this->PendingFrames = 0;
  this->SceneKey.clear();
  this->View.clear();
  this->Camera = nullptr;
}

void vtkSceneVisPlanner::vtkInternals::ComposeReason()
{
  this->CullReasonText = this->Cull.Reason + " (" + this->AdoptedFacts + ")";
  this->RoomsReasonShown = this->Portals ? std::string() : this->Rooms.GetReason();
  if (!this->RoomsReasonShown.empty())
    this->CullReasonText += "; " + this->RoomsReasonShown;
  this->ReasonText = "culling " + this->Cull.Method + ": " + this->CullReasonText +
    "; translucency " + this->Translucency.Method + ": " + this->Translucency.Reason;
}

void vtkSceneVisPlanner::vtkInternals::Adopt(
  const vtkScenePlanChoice& cull, const vtkScenePlanChoice& translucency)
{
  this->Cull = cull;
  this->Translucency = translucency;
  this->AdoptedFacts = this->Inventory.GetFacts().Summary();
  this->ComposeReason();
  this->Planned = true;
  this->Pending.clear();
  this->PendingFrames = 0;
  ++this->Self->PlanCount;
}

vtkScenePlanChoice vtkSceneVisPlanner::vtkInternals::ChooseTranslucency(
  const vtkScenePlanChoice& cull)
{
  const vtkScenePlanFacts& facts = this->Inventory.GetFacts();
  const int translucentActors = this->Inventory.GetTranslucentActors();
  vtkScenePlanChoice sort = vtkScenePlanRule::ChooseTranslucency(facts, cull.Method == "chunked",
    translucentActors > 1, static_cast<std::size_t>(translucentActors));
  if (sort.Method != "bsp-mapper")
    return sort;
  // The BSP mapper replaces a plain mapper only; any other is ordered by the pass.
  for (const vtkScenePlanActorEntry& entry : this->Inventory.GetEntries())
  {
    if (entry.Counted && entry.TranslucentPolygons > 0 &&
      !vtkScenePlanInstaller::IsPlainPolyDataMapper(entry.Mapper) &&
      !vtkBSPSortedPolyDataMapper::SafeDownCast(entry.Mapper))
    {
      sort = { "multi-actor",
        std::string("one translucent actor, drawn by a ") + entry.Mapper->GetClassName() +
          " the planner does not replace: exact order with vtkBSPTranslucentPass" };
    }
  }
  return sort;
}

//------------------------------------------------------------------------------
vtkSceneVisPlanner::vtkSceneVisPlanner()
  : RoomGenerationBudget(vtkAutoRooms::BudgetSeconds)
  , Internals(new vtkInternals(this))
{
}

vtkSceneVisPlanner::~vtkSceneVisPlanner()
{
  this->SetRenderer(nullptr);
  // A renderer that went first took its cullers and pass along; actors may outlive it.
  this->Internals->UndoAll(nullptr);
}

vtkSceneVisPlanner* vtkSceneVisPlanner::Attach(vtkRenderer* renderer)
{
  if (!renderer)
  {
    vtkGenericWarningMacro(<< "vtkSceneVisPlanner::Attach: no renderer: nothing to plan for");
    return nullptr;
  }
  vtkNew<vtkSceneVisPlanner> planner;
  planner->SetRenderer(renderer);
  planner->Internals->StartCommand->Owned = planner;
  return planner;
}

void vtkSceneVisPlanner::SetRenderer(vtkRenderer* renderer)
{
  vtkInternals& in = *this->Internals;
  vtkRenderer* current = in.Renderer;
  if (current == renderer && (renderer || !in.StartCommand))
    return;
  // An Attach() ownership is released when this function ends: it may be what keeps this
  // planner alive.
  vtkSmartPointer<vtkSceneVisPlanner> keep;
  if (vtkSceneVisPlannerStart* start = in.StartCommand)
  {
    start->Planner = nullptr;
    keep = start->Owned;
    start->Owned = nullptr;
    if (current)
    {
      current->RemoveObserver(in.StartTag);
      current->RemoveObserver(in.DeleteTag);
    }
    in.StartCommand = nullptr;
  }
  in.UndoAll(current);
  in.Renderer = renderer;
  this->PlanCount = 0;
  this->InspectionCount = 0;
  this->ViewMeasurementCount = 0;
  if (renderer)
  {
    auto start = vtkSmartPointer<vtkSceneVisPlannerStart>::New();
    start->Planner = this;
    in.StartCommand = start;
    in.StartTag = renderer->AddObserver(vtkCommand::StartEvent, start);
    in.DeleteTag = renderer->AddObserver(vtkCommand::DeleteEvent, start);
  }
  this->Modified();
}

void vtkSceneVisPlanner::RendererDeleted()
{
  // The renderer is about to remove its observers (this one among them, which may own this
  // planner) and to die with its cullers and pass: it must not be touched, not even modified.
  this->Internals->Renderer = nullptr;
  this->Internals->UndoAll(nullptr);
}

vtkRenderer* vtkSceneVisPlanner::GetRenderer()
{
  return this->Internals->Renderer;
}

void vtkSceneVisPlanner::Plan()
{
  const auto start = std::chrono::steady_clock::now();
  vtkInternals& in = *this->Internals;
  vtkRenderer* ren = in.Renderer;
  if (!ren)
  {
    vtkWarningMacro(<< "Plan(): no renderer (SetRenderer): nothing planned");
    return;
  }
  in.Inventory.SetIgnoringModifications(true);
  // The scene: the prop collection and what the observed objects said.
  vtkPropCollection* props = ren->GetViewProps();
  const bool structure = props->GetMTime() != in.PropsTime || !in.Planned;
  const bool portalsChanged =
    in.PortalsChanged || (in.Portals && in.Portals->GetMTime() != in.PortalsTime) || !in.Planned;
  if (portalsChanged)
  {
    if (in.Portals)
      in.Rooms.Clear(); // the application's portals replace generated ones
    in.UsePortals();
    in.PortalsChanged = false;
    in.PortalsTime = in.Portals ? in.Portals->GetMTime() : 0;
  }
  const bool roomsSetting = in.RoomsSettingChanged;
  in.RoomsSettingChanged = false;
  bool sceneChanged = structure || portalsChanged || roomsSetting || in.Inventory.IsDirty();
  if (sceneChanged)
  {
    if (structure || !in.Inventory.Refresh(ren))
      in.Inventory.Inspect(ren);
    in.Inventory.ClearDirty();
    // No portals of the application's: generated ones, tried once per set of actors.
    if (!in.Portals && this->GenerateRooms)
    {
      if (in.Rooms.Update(in.Inventory, structure || roomsSetting || portalsChanged,
            this->RoomGenerationBudget, this->GenerateRoomsInBackground))
        in.UsePortals();
    }
    else if (roomsSetting)
    {
      // Generation turned off: its rooms and its reason go.
      const bool inUse = in.Rooms.GetPortals() != nullptr;
      in.Rooms.Clear();
      if (inUse)
        in.UsePortals();
    }
    this->InspectionCount = in.Inventory.GetNumberOfInspections();
    in.PropsTime = props->GetMTime();
    if (in.Inventory.GetFacts().parts == 0)
    {
      if (!in.WarnedEmpty)
        vtkWarningMacro(<< "the renderer has no visible actors with polydata: nothing installed");
      in.WarnedEmpty = true;
    }
    else
    {
      in.WarnedEmpty = false;
    }
  }
  // Rooms generated in the background that have come: planned for as a change of the scene (the
  // facts' rooms and portals), exactly as if they had been generated in this render.
  if (in.Rooms.Poll(in.Inventory))
  {
    in.UsePortals();
    sceneChanged = true;
  }
  // The view: only the camera's and viewport's parameters that change what is seen.
  vtkCamera* camera = ren->GetActiveCamera();
  bool viewChanged = sceneChanged || camera != in.Camera || camera->GetMTime() != in.CameraTime;
  if (viewChanged)
  {
    ViewKey(ren, in.NewView);
    viewChanged = sceneChanged || in.NewView != in.View;
    in.View.swap(in.NewView);
    in.Camera = camera;
    in.CameraTime = camera->GetMTime();
  }
  else
  {
    const int* size = ren->GetSize();
    if (size[0] != in.Size[0] || size[1] != in.Size[1])
    {
      ViewKey(ren, in.NewView);
      viewChanged = in.NewView != in.View;
      in.View.swap(in.NewView);
    }
  }
  {
    const int* size = ren->GetSize();
    in.Size[0] = size[0];
    in.Size[1] = size[1];
  }
  if (viewChanged && in.Inventory.GetFacts().parts >= vtkScenePlanRule::ManyProps)
  {
    in.Inventory.MeasureView(ren);
    this->ViewMeasurementCount = in.Inventory.GetNumberOfViewMeasurements();
  }
  const vtkScenePlanFacts& facts = in.Inventory.GetFacts();

  if (sceneChanged || viewChanged || !in.Pending.empty())
  {
    const vtkScenePlanChoice cull = vtkScenePlanRule::ChooseCulling(facts);
    const std::vector<double> sceneKey{ static_cast<double>(facts.parts),
      static_cast<double>(facts.polygons), static_cast<double>(facts.triangles),
      facts.translucentFraction, static_cast<double>(in.Inventory.GetTranslucentActors()),
      static_cast<double>(facts.rooms), static_cast<double>(facts.portals) };
    const bool immediate = !in.Planned || sceneKey != in.SceneKey ||
      in.ChooseTranslucency(in.Cull).Method != in.Translucency.Method;
    if (immediate)
    {
      // Props added, removed, shown, hidden or made translucent: the plan follows at once
      // (translucency is a matter of correctness).
      in.SceneKey = sceneKey;
      const vtkScenePlanChoice sort = in.ChooseTranslucency(cull);
      if (!in.Planned || cull.Method != in.Cull.Method || sort.Method != in.Translucency.Method)
        in.Adopt(cull, sort);
      else
      {
        in.Pending.clear();
        in.PendingFrames = 0;
      }
      in.Install(ren);
    }
    else
    {
      if (sceneChanged) // props moved: keep the mappers in step (an input or a mapper changed)
        in.Install(ren);
      if (cull.Method == in.Cull.Method)
      {
        in.Pending.clear();
        in.PendingFrames = 0;
      }
      else
      {
        // A view-driven change: clear of the thresholds by the margin, for SwitchFrames renders.
        bool clear = true;
        if (viewChanged || sceneChanged)
        {
          // The fraction in view is near 1 where it matters: its complement (the fraction out of
          // view) is what is scaled, so that a full view stays clear of the threshold.
          for (const double scale : { 1.0 - this->ViewMargin, 1.0 + this->ViewMargin })
          {
            vtkScenePlanFacts nudged = facts;
            nudged.inView = 1.0 - (1.0 - nudged.inView) * scale;
            nudged.depthComplexity *= scale;
            clear &= vtkScenePlanRule::ChooseCulling(nudged).Method == cull.Method;
          }
        }
        if (!clear || cull.Method != in.Pending)
        {
          in.Pending = clear ? cull.Method : std::string();
          in.PendingFrames = clear ? 1 : 0;
        }
        else
        {
          ++in.PendingFrames;
        }
        if (!in.Pending.empty() && in.PendingFrames >= this->SwitchFrames)
        {
          in.Adopt(cull, in.ChooseTranslucency(cull));
          in.Install(ren);
        }
      }
    }
  }
  // The generated rooms' story moved on (generating, generated, discarded) under the same plan.
  if (in.Planned && !in.Portals && in.Rooms.GetReason() != in.RoomsReasonShown)
    in.ComposeReason();
  in.Inventory.SetIgnoringModifications(false);
  this->LastPlanTime =
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void vtkSceneVisPlanner::SetPortals(vtkPolyData* portals)
{
  if (this->Internals->Portals == portals)
    return;
  this->Internals->Portals = portals;
  this->Internals->PortalsChanged = true;
  this->Modified();
}

vtkPolyData* vtkSceneVisPlanner::GetPortals()
{
  return this->Internals->Portals;
}

void vtkSceneVisPlanner::SetRoomIdArrayName(const char* name)
{
  const std::string value = name ? name : "RoomId";
  if (value == this->Internals->RoomIdArrayName)
    return;
  this->Internals->RoomIdArrayName = value;
  this->Internals->PortalsChanged = true;
  this->Modified();
}

void vtkSceneVisPlanner::SetGenerateRooms(bool generate)
{
  if (generate == this->GenerateRooms)
    return;
  this->GenerateRooms = generate;
  this->Internals->RoomsSettingChanged = true;
  this->Modified();
}

bool vtkSceneVisPlanner::IsRoomGenerationPending() const
{
  return this->Internals->Rooms.IsPending();
}

void vtkSceneVisPlanner::WaitForRoomGeneration()
{
  this->Internals->Rooms.Wait();
}

int vtkSceneVisPlanner::GetNumberOfRoomGenerations() const
{
  return this->Internals->Rooms.GetNumberOfGenerations();
}

const char* vtkSceneVisPlanner::GetRoomIdArrayName() const
{
  return this->Internals->RoomIdArrayName.c_str();
}

const char* vtkSceneVisPlanner::GetCullMethod() const
{
  return this->Internals->Cull.Method.c_str();
}

const char* vtkSceneVisPlanner::GetTranslucencyMethod() const
{
  return this->Internals->Translucency.Method.c_str();
}

const char* vtkSceneVisPlanner::GetCullReason() const
{
  return this->Internals->CullReasonText.c_str();
}

const char* vtkSceneVisPlanner::GetTranslucencyReason() const
{
  return this->Internals->Translucency.Reason.c_str();
}

const char* vtkSceneVisPlanner::GetReason() const
{
  return this->Internals->ReasonText.c_str();
}

const vtkScenePlanFacts& vtkSceneVisPlanner::GetFacts() const
{
  return this->Internals->Inventory.GetFacts();
}

vtkCuller* vtkSceneVisPlanner::GetCuller() const
{
  return this->Internals->Installer.GetCuller();
}

void vtkSceneVisPlanner::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const vtkInternals& in = *this->Internals;
  os << indent << "Renderer: " << static_cast<void*>(in.Renderer.Get()) << "\n";
  os << indent << "CullMethod: " << in.Cull.Method << "\n";
  os << indent << "TranslucencyMethod: " << in.Translucency.Method << "\n";
  os << indent << "Reason: " << in.ReasonText << "\n";
  os << indent << "Facts: " << in.Inventory.GetFacts().Summary() << "\n";
  os << indent << "PlanCount: " << this->PlanCount << "\n";
  os << indent << "InspectionCount: " << this->InspectionCount << "\n";
  os << indent << "ViewMeasurementCount: " << this->ViewMeasurementCount << "\n";
  os << indent << "Pending: " << (in.Pending.empty() ? "(none)" : in.Pending) << " for "
     << in.PendingFrames << " renders\n";
  os << indent << "SwitchFrames: " << this->SwitchFrames << "\n";
  os << indent << "ViewMargin: " << this->ViewMargin << "\n";
  os << indent << "ChunkedMinimumTriangles: " << this->ChunkedMinimumTriangles << "\n";
  os << indent << "RoomGenerationBudget: " << this->RoomGenerationBudget << " s\n";
  os << indent << "GenerateRooms: " << this->GenerateRooms << " ("
     << in.Rooms.GetNumberOfGenerations() << " generations"
     << (in.Rooms.GetPortals() ? ", in use" : "")
     << (in.Rooms.IsPending() ? ", one pending in the background" : "") << ")\n";
  os << indent << "GenerateRoomsInBackground: " << this->GenerateRoomsInBackground << "\n";
  vtkRenderPass* pass = in.Installer.GetPass();
  vtkCuller* culler = in.Installer.GetCuller();
  os << indent << "Culler: " << (culler ? culler->GetClassName() : "(none)") << "\n";
  os << indent << "Portals: " << static_cast<void*>(in.Portals.Get()) << " (room array "
     << in.RoomIdArrayName << ")\n";
  os << indent << "Pass: " << (pass ? pass->GetClassName() : "(none)") << "\n";
  os << indent << "SwappedMappers: " << in.Installer.GetNumberOfSwappedMappers() << "\n";
  os << indent << "ObservedObjects: " << in.Inventory.GetNumberOfObservedObjects() << "\n";
  os << indent << "LastPlanTime: " << this->LastPlanTime << " ms\n";
}
