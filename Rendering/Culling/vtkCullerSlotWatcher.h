/**
 * @file vtkCullerSlotWatcher.h
 * @brief vtkOctreeCuller's UPDATE_ON_EVENTS mode: which slots may have moved, from the
 * ModifiedEvents of the objects their bounds depend on.
 *
 * Private to SceneVis::RenderingCulling. Every object a slot's bounds depend on (the prop, its
 * user matrix, mapper, input, points, upstream algorithms: the list and its limits are in
 * vtkOctreeCuller.h) is observed once, however many slots share it; its ModifiedEvent marks
 * those slots dirty, so a frame re-reads O(changed props). Slots whose dependencies events
 * cannot cover are "polled": re-read every frame.
 */

#ifndef vtkCullerSlotWatcher_h
#define vtkCullerSlotWatcher_h

#include "vtkCallbackCommand.h"
#include "vtkNew.h"

#include "vtkCullerSlot.h"

#include <cstdint>
#include <unordered_map>
#include <vector>

class vtkObject;

class vtkCullerSlotWatcher
{
public:
  /// Watches the slots of @p slots (held by reference; the owner's vector).
  explicit vtkCullerSlotWatcher(std::vector<vtkCullerSlots::Slot>& slots);
  ~vtkCullerSlotWatcher();
  vtkCullerSlotWatcher(const vtkCullerSlotWatcher&) = delete;
  vtkCullerSlotWatcher& operator=(const vtkCullerSlotWatcher&) = delete;

  /// Marks slot @p s to be re-read (once in DirtyList).
  void MarkDirty(std::uint32_t s);
  /// (Re)registers slot @p s: observes what its bounds depend on now, or polls it.
  void Register(std::uint32_t s, bool withProperty, std::vector<vtkObject*>& scratch);
  /// Stops observing for slot @p s.
  void Unregister(std::uint32_t s);
  /// Stops observing everything (all slots unregistered, nothing polled).
  void UnwatchAll();
  /// Rebuilds PolledSlots if a registration changed it.
  void UpdatePolledList();

  /// The objects whose modification can change @p slot's bounds. Returns false when events
  /// cannot cover the prop: it is then polled every frame.
  static bool Dependencies(
    const vtkCullerSlots::Slot& slot, bool withProperty, std::vector<vtkObject*>& deps);

  struct Watch
  {
    unsigned long ModifiedTag = 0, DeleteTag = 0;
    std::vector<std::uint32_t> Slots;
  };
  // Every object observed, with the slots that depend on it (one observer pair per object, so a
  // source shared by 100k actors costs one callback that marks 100k slots).
  std::unordered_map<vtkObject*, Watch> Watches;
  std::vector<std::uint32_t> DirtyList, DirtyWork;
  /// Marked slots whose prop was out of the culler's list when the list was read (another
  /// culler removed it): they stay marked and are re-read once the prop is back.
  std::vector<std::uint32_t> DirtyAbsent;
  std::vector<unsigned char> Dirty;
  std::vector<std::uint32_t> PolledSlots;
  bool PolledSetChanged = true;
  bool EventsActive = false;
  vtkIdType Events = 0;

private:
  static void OnEvent(vtkObject* caller, unsigned long event, void* clientData, void*);
  void WatchObject(vtkObject* object, std::uint32_t s);

  std::vector<vtkCullerSlots::Slot>& Slots;
  vtkNew<vtkCallbackCommand> Callback;
};

#endif
