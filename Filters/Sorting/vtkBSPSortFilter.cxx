#include "vtkBSPSortFilter.h"
#include "vtkObjectFactory.h"
vtkStandardNewMacro(vtkBSPSortFilter);
