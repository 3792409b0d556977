#include "OcclusionQueries.h"

#include <vtkCamera.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkOpenGLBufferObject.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLShaderCache.h>
#include <vtkOpenGLState.h>
#include <vtkOpenGLVertexArrayObject.h>
#include <vtkRenderer.h>
#include <vtkShaderProgram.h>
#include <vtk_glew.h>

#include <chrono>

namespace scenevis
{
namespace bench
{

namespace
{
const char* kVertexShader = "//VTK::System::Dec\n"
                            "in vec4 vertexMC;\n"
                            "uniform mat4 MCDCMatrix;\n"
                            "void main() { gl_Position = MCDCMatrix * vertexMC; }\n";
const char* kFragmentShader = "//VTK::System::Dec\n"
                              "//VTK::Output::Dec\n"
                              "void main() { gl_FragData[0] = vec4(1.0); }\n";

double Ms(std::chrono::steady_clock::time_point since)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - since)
    .count();
}
} // namespace

QueryResult QueryBoxes(vtkRenderer* renderer, const std::vector<std::array<double, 6>>& boxes)
{
  QueryResult result;
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
  if (!window || boxes.empty())
  {
    return result;
  }
  // 12 triangles per box.
  static const int faces[6][4] = { { 0, 1, 3, 2 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 }, { 2, 3, 7, 6 },
    { 0, 2, 6, 4 }, { 1, 3, 7, 5 } };
  std::vector<float> vertices;
  vertices.reserve(boxes.size() * 36 * 3);
  for (const auto& b : boxes)
  {
    for (const auto& f : faces)
    {
      for (const int corner : { f[0], f[1], f[2], f[0], f[2], f[3] })
      {
        vertices.push_back(static_cast<float>(b[corner & 1]));
        vertices.push_back(static_cast<float>(b[2 + ((corner >> 1) & 1)]));
        vertices.push_back(static_cast<float>(b[4 + ((corner >> 2) & 1)]));
      }
    }
  }
  vtkShaderProgram* program =
    window->GetShaderCache()->ReadyShaderProgram(kVertexShader, kFragmentShader, "");
  if (!program)
  {
    return result;
  }
  vtkNew<vtkOpenGLBufferObject> buffer;
  buffer->GenerateBuffer(vtkOpenGLBufferObject::ArrayBuffer);
  buffer->Upload(vertices, vtkOpenGLBufferObject::ArrayBuffer);
  vtkNew<vtkOpenGLVertexArrayObject> vao;
  vao->Bind();
  vao->AddAttributeArray(program, buffer, "vertexMC", 0, 3 * sizeof(float), VTK_FLOAT, 3, false);
  // OpenGL takes column-major matrices: VTK's row-major composite matrix, transposed.
  vtkNew<vtkMatrix4x4> mcdc;
  vtkMatrix4x4::Transpose(
    renderer->GetActiveCamera()->GetCompositeProjectionTransformMatrix(
      renderer->GetTiledAspectRatio(), -1, 1),
    mcdc);
  program->SetUniformMatrix("MCDCMatrix", mcdc);

  vtkOpenGLState* state = window->GetState();
  vtkOpenGLState::ScopedglDepthMask depthMask(state);
  vtkOpenGLState::ScopedglColorMask colorMask(state);
  vtkOpenGLState::ScopedglEnableDisable cull(state, GL_CULL_FACE);
  state->vtkglDepthMask(GL_FALSE);
  state->vtkglColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  state->vtkglEnable(GL_DEPTH_TEST);
  state->vtkglDepthFunc(GL_LEQUAL);
  state->vtkglDisable(GL_CULL_FACE);

  std::vector<GLuint> queries(boxes.size());
  glGenQueries(static_cast<GLsizei>(queries.size()), queries.data());
  auto start = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < boxes.size(); ++i)
  {
    glBeginQuery(GL_ANY_SAMPLES_PASSED, queries[i]);
    glDrawArrays(GL_TRIANGLES, static_cast<GLint>(36 * i), 36);
    glEndQuery(GL_ANY_SAMPLES_PASSED);
  }
  glFlush();
  result.issueMs = Ms(start);
  start = std::chrono::steady_clock::now();
  result.visible.resize(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i)
  {
    GLuint passed = 0;
    glGetQueryObjectuiv(queries[i], GL_QUERY_RESULT, &passed);
    result.visible[i] = passed != 0;
  }
  result.waitMs = Ms(start);
  glDeleteQueries(static_cast<GLsizei>(queries.size()), queries.data());
  vao->Release();
  result.ok = glGetError() == GL_NO_ERROR;
  return result;
}

} // namespace bench
} // namespace scenevis
