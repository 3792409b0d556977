#include "vtkCompactingCuller.h"

#include "vtkCullerCollection.h"
#include "vtkProp.h"
#include "vtkRenderer.h"

#include <algorithm>
#include <cmath>

//------------------------------------------------------------------------------
vtkCompactingCuller::vtkCompactingCuller() = default;

//------------------------------------------------------------------------------
vtkCompactingCuller::~vtkCompactingCuller() = default;

//------------------------------------------------------------------------------
int vtkCompactingCuller::CompactPropList(
  vtkProp** propList, int listLength, const unsigned char* keep)
{
  this->Culled.clear();
  int kept = 0;
  for (int i = 0; i < listLength; ++i)
  {
    if (keep[i])
    {
      propList[kept++] = propList[i];
    }
    else
    {
      this->Culled.push_back(propList[i]);
    }
  }
  std::copy(this->Culled.begin(), this->Culled.end(), propList + kept);
  return kept;
}

//------------------------------------------------------------------------------
double vtkCompactingCuller::SumRenderTimeMultipliers(vtkRenderer* ren, vtkProp** propList,
  int kept, int& initialized, unsigned char* multiplierIsOne, const unsigned int* flagOf)
{
  // Only cullers change the multipliers: while this is the renderer's only culler, a multiplier
  // it set to 1 last frame is still 1.
  const bool flags = multiplierIsOne && flagOf;
  const bool alone = flags && ren && ren->GetCullers()->GetNumberOfItems() == 1 &&
    ren->GetCullers()->GetItemAsObject(0) == this;
  double total = 0.0;
  for (int i = 0; i < kept; ++i)
  {
    if (!initialized)
    {
      if (flags)
      {
        unsigned char& one = multiplierIsOne[flagOf[i]];
        if (!alone || !one)
        {
          propList[i]->SetRenderTimeMultiplier(1.0);
        }
        one = alone ? 1 : 0;
      }
      else
      {
        propList[i]->SetRenderTimeMultiplier(1.0);
      }
      total += 1.0;
    }
    else
    {
      if (flags)
      {
        multiplierIsOne[flagOf[i]] = 0; // an earlier culler may change it from now on
      }
      total += propList[i]->GetRenderTimeMultiplier();
    }
  }
  initialized = 1;
  // The renderer divides by the total: never 0 (or NaN) while props remain.
  if (kept > 0 && !(total > 0.0 && std::isfinite(total)))
  {
    total = static_cast<double>(kept);
  }
  return total;
}

//------------------------------------------------------------------------------
void vtkCompactingCuller::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
