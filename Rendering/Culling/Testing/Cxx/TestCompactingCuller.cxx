// The vtkCuller contract as vtkCompactingCuller keeps it for its subclasses: a culler that keeps
// every other prop, driven the way vtkRenderer::UpdateCulling drives its cullers.
//  - The kept props come first in their relative order, the culled ones after them, and
//    listLength counts the kept ones.
//  - As the first culler (initialized == 0) the kept props' multipliers become 1; after another
//    culler (initialized == 1) they are kept, and the total is their sum.
//  - The total is never 0 (or NaN) while props remain.
//  - A culler that remembers "multiplier already 1" per prop (vtkOctreeCuller does, for 50k-prop
//    lists) skips the writes only while it is the renderer's only culler, and forgets what it
//    remembered as soon as another culler runs first and may change the multipliers.

#include "vtkCompactingCuller.h"

#include <vtkActor.h>
#include <vtkCullerCollection.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

namespace
{
/// Keeps the props at even list positions; remembers multipliers per prop if asked.
class EveryOtherCuller : public vtkCompactingCuller
{
public:
  static EveryOtherCuller* New();
  vtkTypeMacro(EveryOtherCuller, vtkCompactingCuller);

  double Cull(vtkRenderer* ren, vtkProp** propList, int& listLength, int& initialized) override
  {
    std::vector<unsigned char> keep(static_cast<std::size_t>(listLength));
    std::vector<unsigned int> flagOf;
    for (int i = 0; i < listLength; ++i)
    {
      keep[static_cast<std::size_t>(i)] = i % 2 == 0 ? 1 : 0;
      if (i % 2 == 0)
      {
        flagOf.push_back(static_cast<unsigned int>(i)); // the flag of the prop first at i
      }
    }
    listLength = this->CompactPropList(propList, listLength, keep.data());
    this->Flags.resize(static_cast<std::size_t>(listLength) * 2 + 1, 0);
    return this->SumRenderTimeMultipliers(ren, propList, listLength, initialized,
      this->RememberOnes ? this->Flags.data() : nullptr,
      this->RememberOnes ? flagOf.data() : nullptr);
  }

  bool RememberOnes = false;
  std::vector<unsigned char> Flags;
};
vtkStandardNewMacro(EveryOtherCuller);

bool Check(bool ok, const std::string& what)
{
  std::cout << (ok ? "ok   " : "FAIL ") << what << "\n";
  return ok;
}
} // namespace

int TestCompactingCuller(int, char*[])
{
  bool ok = true;
  std::vector<vtkSmartPointer<vtkActor>> actors;
  for (int i = 0; i < 5; ++i)
  {
    actors.push_back(vtkSmartPointer<vtkActor>::New());
  }
  auto list = [&actors]()
  {
    std::vector<vtkProp*> props;
    for (const auto& a : actors)
    {
      props.push_back(a);
    }
    return props;
  };

  vtkNew<vtkRenderer> ren;
  vtkNew<EveryOtherCuller> culler;
  ren->GetCullers()->RemoveAllItems();
  ren->AddCuller(culler);

  // First culler: kept ones first in order, culled after in order, multipliers 1.
  for (auto& a : actors)
  {
    a->SetRenderTimeMultiplier(0.5);
  }
  std::vector<vtkProp*> props = list();
  int length = 5, initialized = 0;
  double total = culler->Cull(ren, props.data(), length, initialized);
  ok &= Check(length == 3 && initialized == 1, "three of five kept, initialized set");
  ok &= Check(props[0] == actors[0] && props[1] == actors[2] && props[2] == actors[4] &&
      props[3] == actors[1] && props[4] == actors[3],
    "kept props first and culled ones after, each in their order");
  ok &= Check(total == 3.0 && actors[0]->GetRenderTimeMultiplier() == 1.0 &&
      actors[4]->GetRenderTimeMultiplier() == 1.0 && actors[1]->GetRenderTimeMultiplier() == 0.5,
    "first culler: kept multipliers set to 1, culled ones untouched, total 3");

  // After another culler: multipliers kept and summed.
  actors[0]->SetRenderTimeMultiplier(0.25);
  props = list();
  length = 5;
  initialized = 1;
  total = culler->Cull(ren, props.data(), length, initialized);
  ok &= Check(std::abs(total - 2.25) < 1e-12 && actors[0]->GetRenderTimeMultiplier() == 0.25,
    "after another culler: multipliers kept, total their sum");

  // Never 0 while props remain.
  for (auto& a : actors)
  {
    a->SetRenderTimeMultiplier(0.0);
  }
  props = list();
  length = 5;
  initialized = 1;
  total = culler->Cull(ren, props.data(), length, initialized);
  ok &= Check(total == 3.0, "all kept multipliers 0: the total is the number kept, not 0");
  props = list();
  length = 0;
  initialized = 0;
  total = culler->Cull(ren, props.data(), length, initialized);
  ok &= Check(total == 0.0 && length == 0, "an empty list: total 0");

  // Remembered ones: skipped only while alone, forgotten when another culler runs first.
  culler->RememberOnes = true;
  culler->Flags.clear();
  props = list();
  length = 5;
  initialized = 0;
  culler->Cull(ren, props.data(), length, initialized);
  ok &= Check(actors[0]->GetRenderTimeMultiplier() == 1.0, "alone: multipliers 1");
  actors[0]->SetRenderTimeMultiplier(0.125); // another culler runs first and changes it
  props = list();
  length = 5;
  initialized = 1;
  culler->Cull(ren, props.data(), length, initialized);
  props = list();
  length = 5;
  initialized = 0; // the other culler is gone: alone again
  total = culler->Cull(ren, props.data(), length, initialized);
  ok &= Check(actors[0]->GetRenderTimeMultiplier() == 1.0 && total == 3.0,
    "alone again after another culler changed a multiplier: it is set to 1 again");
  // Not alone: every multiplier written.
  vtkNew<EveryOtherCuller> other;
  ren->AddCuller(other);
  actors[4]->SetRenderTimeMultiplier(0.125);
  props = list();
  length = 5;
  initialized = 0;
  total = culler->Cull(ren, props.data(), length, initialized);
  ok &= Check(actors[4]->GetRenderTimeMultiplier() == 1.0 && total == 3.0,
    "with another culler in the renderer: nothing skipped");
  return ok ? 0 : 1;
}
