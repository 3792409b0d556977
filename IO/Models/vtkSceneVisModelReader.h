/**
 * @class   vtkSceneVisModelReader
 * @brief   Reads a surface model or a glTF/VRML scene as one polydata with parts and colours.
 *
 * The file's extension picks VTK's reader: .vtp (vtkXMLPolyDataReader), .vtk (legacy polydata),
 * .ply, .stl, .obj, and the scene formats .glb/.gltf (vtkGLTFImporter) and .wrl (VRML 2.0,
 * vtkVRMLImporter). A scene's actors are merged into the one output, each with its matrix
 * applied, and the output gets two cell arrays:
 *  - "PartId" (vtkIdTypeArray): the actor's index in import order;
 *  - "Colors" (RGBA unsigned char, the cell scalars): the actor's diffuse colour and opacity.
 * Other formats keep the arrays their files have. VRML parts also keep the point scalars
 * vtkVRMLImporter gives them, which a mapper prefers by default: draw the parts' colours with
 * mapper->SetScalarModeToUseCellData().
 *
 * VRML text is first passed through InlineVrmlMaterialUses(): VTK 9.1's importer ignores
 * `material USE NAME`, so KiCad parts (one DEF per material, USE for every shape) would come out
 * white and opaque.
 *
 * After reading, a cell that names a point the file does not have is an error (every later step
 * would read out of bounds), and with RemoveNonFiniteCells on (the default) the cells that use a
 * NaN or infinite point are removed (GetNumberOfRemovedCells()); the points themselves are moved
 * onto a finite one, because VTK's point bounds skip NaN points but not infinite ones, and one
 * such point would leave a fitted camera looking at nothing.
 *
 * Errors: a missing or unreadable file, an unknown extension, a file its reader rejects, a file
 * without cells, and a file whose every cell uses a NaN/Inf point all give ONE error (one line,
 * vtkErrorMacro, also kept in GetErrorMessage()), an ErrorCode and an empty output. The errors and
 * warnings of VTK's readers (and of their executives) are caught and folded into that line instead
 * of reaching the output window (warnings of a read that succeeds are dropped); objects the reader
 * cannot observe, such as the glTF importer's document loader, may still log. Exceptions that
 * VTK's glTF loader lets through are caught too.
 *
 * VTK 9.1's PLY and glTF readers crash the process on some malformed files
 * (Testing/BadInput/TestMalformedModels.cxx lists them). With ReadInChildProcess on, VTK's reader
 * runs in a child process (vtkIsolatedRead.h): such a crash is one error ("VTK's reader crashed on
 * it (signal ...)") and an empty output, as the `scenevis` tool reads files. Off by default: it
 * costs writing and reading the model once more.
 *
 * Usage:
 * @code
 * vtkNew<vtkSceneVisModelReader> reader;
 * reader->SetFileName("engine.glb");
 * reader->Update();
 * if (reader->GetOutput()->GetNumberOfCells() == 0) std::cerr << reader->GetErrorMessage();
 * @endcode
 *
 * The importers make mappers and a render window through VTK's object factories, so this module
 * initialises VTK::RenderingOpenGL2 itself; nothing is rendered.
 *
 * @sa vtkGLTFImporter vtkVRMLImporter vtkXMLPolyDataReader
 */

#ifndef vtkSceneVisModelReader_h
#define vtkSceneVisModelReader_h

#include "SceneVisIOModelsModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"
#include "vtkSmartPointer.h" // For vtkSmartPointer

#include <string> // For std::string

class SCENEVISIOMODELS_EXPORT vtkSceneVisModelReader : public vtkPolyDataAlgorithm
{
public:
  static vtkSceneVisModelReader* New();
  vtkTypeMacro(vtkSceneVisModelReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The model file; its extension (any case) picks the reader.
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  ///@{
  /// Remove the cells that use a NaN or infinite point (default on).
  vtkSetMacro(RemoveNonFiniteCells, bool);
  vtkGetMacro(RemoveNonFiniteCells, bool);
  vtkBooleanMacro(RemoveNonFiniteCells, bool);
  ///@}

  ///@{
  /// Run VTK's reader in a child process (POSIX fork), so that a reader crash on a malformed file
  /// is an error, not the end of the program (default off). .vtp files are read in this process
  /// either way: VTK's XML reader checks what it reads.
  vtkSetMacro(ReadInChildProcess, bool);
  vtkGetMacro(ReadInChildProcess, bool);
  vtkBooleanMacro(ReadInChildProcess, bool);
  ///@}

  /// How many cells the last read removed for NaN/Inf points.
  vtkGetMacro(NumberOfRemovedCells, vtkIdType);

  /// The last read's error in one line ("" after a successful read).
  const char* GetErrorMessage() const { return this->ErrorMessage.c_str(); }

  /// Whether the extension of @p fileName is one this reader reads.
  static bool CanReadFile(const char* fileName);

#ifndef __VTK_WRAP__
  /**
   * The model in @p path read in one call, as a polydata of its own; nullptr when it cannot be
   * read, and @p error (if given) then holds the one-line error, which is not printed.
   * @p removeNonFiniteCells: as SetRemoveNonFiniteCells() (the `scenevis` tool passes false: it
   * removes such cells itself and says how many).
   */
  static vtkSmartPointer<vtkPolyData> LoadFile(
    const std::string& path, std::string* error = nullptr, bool removeNonFiniteCells = true);
#endif

  /**
   * VRML text with every `material USE NAME` replaced by a copy of the `material DEF NAME
   * Material { ... }` node defined earlier in the text. Unknown names are left as they are; text
   * without USE is returned unchanged.
   */
  static std::string InlineVrmlMaterialUses(const std::string& text);

  /**
   * Removes the cells of @p polydata that use a NaN or infinite point and returns how many; the
   * points themselves are moved onto a finite one (point data stays as it is).
   */
  static vtkIdType RemoveCellsWithNonFinitePoints(vtkPolyData* polydata);

  /**
   * The first cell of @p polydata (verts, lines, polys, strips order) that names a point it does
   * not have, as "cell C uses point P of only N"; empty when every id is valid.
   */
  static std::string DescribeBadPointId(vtkPolyData* polydata);

protected:
  vtkSceneVisModelReader();
  ~vtkSceneVisModelReader() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* FileName = nullptr;
  bool RemoveNonFiniteCells = true;
  bool ReadInChildProcess = false;
  vtkIdType NumberOfRemovedCells = 0;
  std::string ErrorMessage;

private:
  vtkSceneVisModelReader(const vtkSceneVisModelReader&) = delete;
  void operator=(const vtkSceneVisModelReader&) = delete;
};

#endif
