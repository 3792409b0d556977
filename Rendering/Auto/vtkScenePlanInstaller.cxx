#include "vtkScenePlanInstaller.h"

#include "vtkActor.h"
#include "vtkBSPSortedPolyDataMapper.h"
#include "vtkBSPTranslucentPass.h"
#include "vtkChunkedPolyDataMapper.h"
#include "vtkCullerCollection.h"
#include "vtkFrustumCoverageCuller.h"
#include "vtkOcclusionCuller.h"
#include "vtkOrderedTranslucentPass.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkPortalCuller.h"
#include "vtkRenderer.h"

#include <cstring>

vtkScenePlanInstaller::vtkScenePlanInstaller(vtkObject* owner)
  : Owner(owner)
  , OrderedPass(vtkSmartPointer<vtkOrderedTranslucentPass>::New())
  , SortedPass(vtkSmartPointer<vtkBSPTranslucentPass>::New())
  , PlainPass(vtkSmartPointer<vtkOrderedTranslucentPass>::New())
{
  this->OrderedPass->SetTranslucentPass(this->SortedPass);
}

vtkScenePlanInstaller::~vtkScenePlanInstaller() = default;

bool vtkScenePlanInstaller::IsPlainPolyDataMapper(vtkMapper* mapper)
{
  return mapper && std::strcmp(mapper->GetClassName(), "vtkOpenGLPolyDataMapper") == 0;
}

vtkCuller* vtkScenePlanInstaller::GetCuller() const
{
  return this->Installed;
}

void vtkScenePlanInstaller::SetPortals(vtkPolyData* portals, const char* roomIdArrayName)
{
  this->Portals = portals;
  this->RoomIdArrayName = roomIdArrayName ? roomIdArrayName : "RoomId";
  if (this->PortalCuller)
  {
    this->PortalCuller->SetPortals(portals);
    this->PortalCuller->SetRoomIdArrayName(this->RoomIdArrayName.c_str());
  }
}

void vtkScenePlanInstaller::SetCellRooms(const vtkScenePlanRooms::CellRooms& rooms)
{
  if (this->PortalCuller)
    for (const auto& actorRooms : this->CellRooms)
      this->PortalCuller->SetPropCellRooms(actorRooms.first, nullptr);
  this->CellRooms = rooms;
  this->GiveCellRooms();
}

void vtkScenePlanInstaller::GiveCellRooms()
{
  if (this->PortalCuller)
    for (const auto& actorRooms : this->CellRooms)
      this->PortalCuller->SetPropCellRooms(actorRooms.first, actorRooms.second);
}

int vtkScenePlanInstaller::GetNumberOfSwappedMappers() const
{
  int swapped = 0;
  for (const auto& swap : this->Swaps)
    swapped += swap.second.Installed ? 1 : 0;
  return swapped;
}

vtkMapper* vtkScenePlanInstaller::ApplicationMapper(vtkActor* actor)
{
  vtkMapper* current = actor->GetMapper();
  auto found = this->Swaps.find(actor);
  if (found == this->Swaps.end())
    return current;
  MapperSwap& swap = found->second;
  if (swap.Installed && current == swap.Installed)
    return swap.Original;
  if (current != swap.Original)
    this->Swaps.erase(found); // the application set a mapper of its own: it wins
  return current;
}

void vtkScenePlanInstaller::InstallCuller(vtkRenderer* ren, const std::string& cull)
{
  if (cull == "octree" || cull == "occlusion")
  {
    if (!this->Culler)
      this->Culler = vtkSmartPointer<vtkOcclusionCuller>::New();
    // One culler for both: switching keeps its hierarchy.
    this->Culler->SetOcclusionCulling(cull == "occlusion");
    this->PlaceCuller(ren, this->Culler);
  }
  else if (cull == "portals" && this->Portals)
  {
    if (!this->PortalCuller)
    {
      this->PortalCuller = vtkSmartPointer<vtkPortalCuller>::New();
      this->PortalCuller->SetPortals(this->Portals);
      this->PortalCuller->SetRoomIdArrayName(this->RoomIdArrayName.c_str());
      this->GiveCellRooms();
    }
    this->PlaceCuller(ren, this->PortalCuller);
  }
  else
  {
    this->PlaceCuller(ren, nullptr);
  }
}

void vtkScenePlanInstaller::PlaceCuller(vtkRenderer* ren, vtkCuller* wanted)
{
  vtkCullerCollection* cullers = ren->GetCullers();
  if (this->Installed && this->Installed != wanted)
  {
    ren->RemoveCuller(this->Installed);
    this->Installed = nullptr;
  }
  if (!wanted)
  {
    for (const auto& culler : this->RemovedCullers)
      ren->AddCuller(culler);
    this->RemovedCullers.clear();
    return;
  }
  if (this->Installed == wanted && cullers->IsItemPresent(wanted))
    return;
  // Our cullers do what vtkFrustumCoverageCuller does, for a fraction of the cost.
  vtkCollectionSimpleIterator it;
  cullers->InitTraversal(it);
  std::vector<vtkCuller*> coverage;
  while (vtkCuller* culler = cullers->GetNextCuller(it))
    if (vtkFrustumCoverageCuller::SafeDownCast(culler))
      coverage.push_back(culler);
  for (vtkCuller* culler : coverage)
  {
    this->RemovedCullers.emplace_back(culler);
    cullers->RemoveItem(culler);
  }
  ren->AddCuller(wanted);
  this->Installed = wanted;
}

void vtkScenePlanInstaller::InstallPass(vtkRenderer* ren, vtkRenderPass* pass)
{
  vtkRenderPass* current = ren->GetPass();
  if (current && current != this->InstalledPass)
  {
    if (pass && !this->WarnedPass)
    {
      this->WarnedPass = true;
      vtkWarningWithObjectMacro(this->Owner, << "the renderer has its own render pass ("
                                             << current->GetClassName()
                                             << "): translucency is left to it");
    }
    this->InstalledPass = nullptr;
    return;
  }
  if (current != pass)
    ren->SetPass(pass);
  this->InstalledPass = pass;
}

void vtkScenePlanInstaller::SwapMapper(vtkActor* actor, bool sorted, bool chunked)
{
  vtkMapper* own = this->ApplicationMapper(actor);
  auto found = this->Swaps.find(actor);
  if (!sorted && !chunked)
  {
    if (found != this->Swaps.end() && found->second.Installed)
    {
      actor->SetMapper(found->second.Original);
      found->second.Installed = nullptr;
    }
    return;
  }
  if (found == this->Swaps.end())
  {
    if (!IsPlainPolyDataMapper(own))
      return; // an application's own mapper class: leave it
    MapperSwap swap;
    swap.Actor = actor;
    swap.Original = own;
    found = this->Swaps.emplace(actor, swap).first;
  }
  MapperSwap& swap = found->second;
  vtkMapper* wanted = nullptr;
  if (sorted)
  {
    if (!swap.Sorted)
      swap.Sorted = vtkSmartPointer<vtkBSPSortedPolyDataMapper>::New();
    wanted = swap.Sorted;
  }
  else
  {
    if (!swap.Chunked)
      swap.Chunked = vtkSmartPointer<vtkChunkedPolyDataMapper>::New();
    wanted = swap.Chunked;
  }
  if (swap.Installed != wanted || swap.CopiedTime != swap.Original->GetMTime())
  {
    // Same input, colouring, lookup table and clipping planes as the application's mapper.
    // vtkPolyDataMapper's copy, not vtkOpenGLPolyDataMapper's: that one goes through VTK 9.1's
    // deprecated shader-code accessors (a warning each) for shader code we do not carry over.
    static_cast<vtkPolyDataMapper*>(wanted)->vtkPolyDataMapper::ShallowCopy(swap.Original);
    swap.CopiedTime = swap.Original->GetMTime();
  }
  if (actor->GetMapper() != wanted)
    actor->SetMapper(wanted);
  swap.Installed = wanted;
}

void vtkScenePlanInstaller::Install(vtkRenderer* ren, const std::string& cull,
  const std::string& translucency, vtkScenePlanInventory& inventory,
  vtkIdType chunkedMinimumTriangles)
{
  this->InstallCuller(ren, cull);
  if (translucency == "multi-actor")
    this->InstallPass(ren, this->OrderedPass);
  else if (translucency == "bsp-mapper")
    this->InstallPass(ren, this->PlainPass);
  else
    this->InstallPass(ren, nullptr);

  // Mappers: the BSP mapper on the one translucent actor, chunks in the big opaque ones.
  const bool passInstalled = this->InstalledPass != nullptr;
  for (vtkScenePlanActorEntry& entry : inventory.GetEntries())
  {
    if (!entry.Counted)
      continue;
    const bool sorted =
      translucency == "bsp-mapper" && passInstalled && entry.TranslucentPolygons > 0;
    const bool chunked = cull == "chunked" && entry.TranslucentPolygons == 0 &&
      entry.Triangles >= chunkedMinimumTriangles;
    const vtkMapper* before = entry.Actor->GetMapper();
    this->SwapMapper(entry.Actor, sorted, chunked);
    if (entry.Actor->GetMapper() != before)
      entry.ActorTime = entry.Actor->GetMTime(); // our own change, not the application's
  }
  // Swapped actors that left the plan (hidden, removed) get their own mapper back.
  for (auto it = this->Swaps.begin(); it != this->Swaps.end();)
  {
    vtkActor* actor = it->second.Actor;
    if (!actor)
    {
      it = this->Swaps.erase(it);
      continue;
    }
    if (!inventory.Contains(actor) && it->second.Installed)
    {
      if (actor->GetMapper() == it->second.Installed)
        actor->SetMapper(it->second.Original);
      it->second.Installed = nullptr;
    }
    ++it;
  }
}

void vtkScenePlanInstaller::Uninstall(vtkRenderer* ren)
{
  if (ren)
  {
    this->InstallCuller(ren, "none");
    if (this->InstalledPass && ren->GetPass() == this->InstalledPass)
      ren->SetPass(nullptr);
  }
  // The cullers' hierarchies are of this renderer's props: a next renderer gets new ones.
  this->Culler = nullptr;
  this->PortalCuller = nullptr;
  this->Installed = nullptr;
  this->RemovedCullers.clear();
  this->InstalledPass = nullptr;
  for (auto& entry : this->Swaps)
  {
    vtkActor* actor = entry.second.Actor;
    if (actor && entry.second.Installed && actor->GetMapper() == entry.second.Installed)
      actor->SetMapper(entry.second.Original);
  }
  this->Swaps.clear();
}
