#include "vtkMapperPolyData.h"

#include "vtkCompositeDataDisplayAttributes.h"
#include "vtkCompositeDataSet.h"
#include "vtkCompositePolyDataMapper2.h"
#include "vtkMapper.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPolyData.h"

namespace
{
/**
 * The visible leaves of a composite dataset below @p node (visible: @p visible, unless its own
 * block visibility in @p attributes says otherwise; children inherit), into @p leaves. False
 * when a leaf is not a polydata.
 */
bool CollectVisibleLeaves(vtkDataObject* node, bool visible,
  const vtkCompositeDataDisplayAttributes* attributes, std::vector<vtkPolyData*>& leaves)
{
  if (!node)
  {
    return true;
  }
  if (attributes && attributes->HasBlockVisibility(node))
  {
    visible = attributes->GetBlockVisibility(node);
  }
  if (auto* blocks = vtkMultiBlockDataSet::SafeDownCast(node))
  {
    for (unsigned int i = 0; i < blocks->GetNumberOfBlocks(); ++i)
    {
      if (!CollectVisibleLeaves(blocks->GetBlock(i), visible, attributes, leaves))
      {
        return false;
      }
    }
    return true;
  }
  if (auto* partitions = vtkPartitionedDataSet::SafeDownCast(node))
  {
    for (unsigned int i = 0; i < partitions->GetNumberOfPartitions(); ++i)
    {
      if (!CollectVisibleLeaves(
            partitions->GetPartitionAsDataObject(i), visible, attributes, leaves))
      {
        return false;
      }
    }
    return true;
  }
  auto* polydata = vtkPolyData::SafeDownCast(node);
  if (!polydata)
  {
    return false;
  }
  if (visible && polydata->GetNumberOfCells() > 0)
  {
    leaves.push_back(polydata);
  }
  return true;
}
} // namespace

bool vtkMapperPolyData::Collect(
  vtkMapper* mapper, std::vector<vtkPolyData*>& leaves, bool uniformOnly)
{
  leaves.clear();
  vtkDataObject* input = mapper ? mapper->GetInputDataObject(0, 0) : nullptr;
  // dynamic_cast, not SafeDownCast: the occlusion culler asks this of every visible prop, and
  // SafeDownCast compares class names along the hierarchy.
  if (auto* polydata = dynamic_cast<vtkPolyData*>(input))
  {
    leaves.push_back(polydata);
    return true;
  }
  if (!vtkCompositeDataSet::SafeDownCast(input))
  {
    return false;
  }
  const vtkCompositeDataDisplayAttributes* attributes = nullptr;
  if (auto* compositeMapper = vtkCompositePolyDataMapper2::SafeDownCast(mapper))
  {
    attributes = compositeMapper->GetCompositeDataDisplayAttributes();
    if (uniformOnly && attributes &&
      (attributes->HasBlockColors() || attributes->HasBlockOpacities() ||
        attributes->HasBlockMaterials()))
    {
      return false;
    }
  }
  return CollectVisibleLeaves(input, true, attributes, leaves);
}
