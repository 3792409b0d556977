#ifndef vtkBSPSortFilter_h
#define vtkBSPSortFilter_h
#include "SceneVisFiltersSortingModule.h"
#include "vtkPolyDataAlgorithm.h"
class SCENEVISFILTERSSORTING_EXPORT vtkBSPSortFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkBSPSortFilter* New();
  vtkTypeMacro(vtkBSPSortFilter, vtkPolyDataAlgorithm);
protected:
  vtkBSPSortFilter() = default;
  ~vtkBSPSortFilter() override = default;
private:
  vtkBSPSortFilter(const vtkBSPSortFilter&) = delete;
  void operator=(const vtkBSPSortFilter&) = delete;
};
#endif
