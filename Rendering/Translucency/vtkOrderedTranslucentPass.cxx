#include "vtkOrderedTranslucentPass.h"

#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkTranslucentPass.h"

vtkStandardNewMacro(vtkOrderedTranslucentPass);

//------------------------------------------------------------------------------
vtkOrderedTranslucentPass::vtkOrderedTranslucentPass()
{
  // vtkRenderStepsPass already defaults to vtkTranslucentPass; set it explicitly so the
  // guarantee this class makes does not depend on that default.
  vtkNew<vtkTranslucentPass> translucent;
  this->SetTranslucentPass(translucent);
}

//------------------------------------------------------------------------------
void vtkOrderedTranslucentPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
