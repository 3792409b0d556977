/**
 * @file    vtkIsolatedRead.h
 * @brief   Runs a model loader in a child process, so that a reader that crashes on a malformed
 *          file costs the child, not the program.
 *
 * VTK 9.1's PLY and glTF readers crash the process on some malformed files (heap corruption,
 * wild pointers, endless recursion; Testing/BadInput/TestMalformedModels.cxx lists them). A
 * program that reads files it cannot trust runs the loader here: the child (POSIX fork) loads,
 * writes the model to a temporary raw .vtp file ($TMPDIR, else /tmp) and exits; the parent reads
 * it back and removes it. A crash becomes one line ("cannot read 'F': VTK's reader crashed on it
 * (signal 11, Segmentation fault)"), the loader's own error comes back through a pipe, the child's
 * stderr goes to /dev/null (some readers print a line per element) and it dumps no core. Costs
 * writing and reading the model once more. When the temporary file or the fork cannot be had,
 * the loader runs in this process.
 *
 * Plain functions (not wrapped for Python); vtkSceneVisModelReader::ReadInChildProcess uses it.
 */
#ifndef vtkIsolatedRead_h
#define vtkIsolatedRead_h

#include "SceneVisIOModelsModule.h" // For export macro

#include <vtkPolyData.h>     // For vtkSmartPointer<vtkPolyData>
#include <vtkSmartPointer.h> // For vtkSmartPointer

#include <functional> // For std::function
#include <string>     // For std::string

struct SCENEVISIOMODELS_EXPORT vtkIsolatedRead
{
  /// Loads a model, or returns null and says why in @p error.
  using Loader = std::function<vtkSmartPointer<vtkPolyData>(std::string* error)>;

  /// @p load run in a child process (see the file comment); @p path names the file in messages.
  static vtkSmartPointer<vtkPolyData> Run(
    const std::string& path, const Loader& load, std::string* error);
};

#endif
