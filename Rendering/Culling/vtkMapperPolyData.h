/**
 * @class   vtkMapperPolyData
 * @brief   The polygons a mapper draws, for code that reads them beside the mapper: the
 *          occlusion culler's occluders, the BSP translucent pass's sorting.
 *
 * A vtkPolyDataMapper draws its vtkPolyData input. A composite mapper (vtkCompositePolyDataMapper2,
 * as ParaView's representations and VTK's multiblock readers use: glTF, VRML, CAD) draws the
 * visible polydata leaves of a vtkMultiBlockDataSet or vtkPartitionedDataSet (tree), each block
 * visible unless its display attributes say otherwise, children inheriting. Module-private
 * (not wrapped); exported for SceneVis::RenderingTranslucency.
 */

#ifndef vtkMapperPolyData_h
#define vtkMapperPolyData_h

#include "SceneVisRenderingCullingModule.h" // For export macro

#include <vector>

class vtkMapper;
class vtkPolyData;

class SCENEVISRENDERINGCULLING_EXPORT vtkMapperPolyData
{
public:
  /**
   * The non-empty polydata @p mapper draws, into @p leaves (cleared first). False when it draws
   * something else (an input that is neither a polydata nor a composite of polydata leaves), or,
   * with @p uniformOnly, when a composite's blocks have colours, opacities or materials of their
   * own (drawn unlike the actor's property). A polydata input is returned even when empty.
   */
  static bool Collect(vtkMapper* mapper, std::vector<vtkPolyData*>& leaves, bool uniformOnly);
};

#endif
