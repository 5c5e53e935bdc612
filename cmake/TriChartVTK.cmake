# The VTK layer: filter modules, Python wrapping, ParaView plugin, app, VTK tests.
# Any VTK 9.1+ works; the README's set-up points VTK_DIR at ParaView 5.11's VTK so that one
# build serves Python, pvpython, the plugin and the app.

if (TRICHART_BUILD_PARAVIEW_PLUGIN)
  # ParaView brings its own VTK; look for it first so both agree.
  find_package(ParaView 5.10 QUIET)
endif ()

set(_tc_vtk_components
  CommonCore CommonDataModel CommonExecutionModel FiltersCore FiltersGeneral FiltersGeometry FiltersSources CommonSystem
  IOCore IOGeometry IOLegacy IOPLY IOXML IOImage ImagingCore
  RenderingCore RenderingOpenGL2 RenderingAnnotation RenderingFreeType InteractionStyle
  TestingCore TestingRendering)
if (TRICHART_WRAP_PYTHON)
  list(APPEND _tc_vtk_components WrappingPythonCore Python)
  set(Python3_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "Python used for wrapping and tests")
endif ()
if (TRICHART_BUILD_APP)
  list(APPEND _tc_vtk_components GUISupportQt FiltersModeling)
endif ()
find_package(VTK 9.1 REQUIRED COMPONENTS ${_tc_vtk_components})
message(STATUS "TriChart: VTK ${VTK_VERSION} from ${VTK_DIR}")

# The ParaView representation depends on ParaView's RemotingViews: only with ParaView.
set(_tc_paraview_module_files)
set(_tc_paraview_modules)
if (TRICHART_BUILD_PARAVIEW_PLUGIN AND ParaView_FOUND)
  set(_tc_paraview_module_files ${CMAKE_SOURCE_DIR}/filters/ParaView/vtk.module)
  set(_tc_paraview_modules TriChart::ParaView)
endif ()

set(BUILD_SHARED_LIBS ON)
vtk_module_scan(
  MODULE_FILES
    ${CMAKE_SOURCE_DIR}/filters/Common/vtk.module
    ${CMAKE_SOURCE_DIR}/filters/IO/vtk.module
    ${CMAKE_SOURCE_DIR}/filters/Preparation/vtk.module
    ${CMAKE_SOURCE_DIR}/filters/Curvature/vtk.module
    ${CMAKE_SOURCE_DIR}/filters/Features/vtk.module
    ${CMAKE_SOURCE_DIR}/filters/BaseComplex/vtk.module
    ${CMAKE_SOURCE_DIR}/filters/GeometryImages/vtk.module
    ${CMAKE_SOURCE_DIR}/filters/Rendering/vtk.module
    ${CMAKE_SOURCE_DIR}/filters/Skinning/vtk.module
    ${CMAKE_SOURCE_DIR}/filters/Multilevel/vtk.module
    ${_tc_paraview_module_files}
  REQUEST_MODULES
    TriChart::Common TriChart::IO TriChart::Preparation TriChart::Curvature TriChart::Features
    TriChart::BaseComplex TriChart::GeometryImages TriChart::Rendering TriChart::Skinning
    TriChart::Multilevel ${_tc_paraview_modules}
  PROVIDES_MODULES _tc_modules
  ENABLE_TESTS OFF)
vtk_module_build(
  MODULES ${_tc_modules}
  INSTALL_EXPORT TriChart
  ARCHIVE_DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY_DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME_DESTINATION ${CMAKE_INSTALL_BINDIR}
  HEADERS_DESTINATION include/trichart
  CMAKE_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/trichart
  ENABLE_WRAPPING ON
  VERSION ${PROJECT_VERSION}
  SOVERSION ${PROJECT_VERSION_MAJOR})

# The filter modules that users see (the Common module is internal); with ParaView, also the
# representation (wrapped for pvpython, whose paraview.modules it imports).
set(TRICHART_FILTER_MODULES
  TriChart::IO TriChart::Preparation TriChart::Curvature TriChart::Features TriChart::BaseComplex
  TriChart::GeometryImages TriChart::Rendering TriChart::Skinning TriChart::Multilevel
  ${_tc_paraview_modules})

if (TRICHART_WRAP_PYTHON)
  execute_process(
    COMMAND ${Python3_EXECUTABLE} -c
      "import sys; print('lib/python{}.{}/dist-packages'.format(*sys.version_info[:2]))"
    OUTPUT_VARIABLE TRICHART_PYTHON_DESTINATION OUTPUT_STRIP_TRAILING_WHITESPACE)
  set(TRICHART_PYTHON_DESTINATION "${TRICHART_PYTHON_DESTINATION}" CACHE STRING
    "Python package folder, relative to the install prefix")
  vtk_module_wrap_python(
    MODULES ${TRICHART_FILTER_MODULES}
    PYTHON_PACKAGE trichart
    MODULE_DESTINATION ${TRICHART_PYTHON_DESTINATION}
    LIBRARY_DESTINATION ${CMAKE_INSTALL_LIBDIR}
    CMAKE_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/trichart
    INSTALL_EXPORT TriChartPython
    INSTALL_HEADERS OFF
    BUILD_STATIC OFF
    TARGET TriChart::Python)
endif ()

if (TRICHART_BUILD_PARAVIEW_PLUGIN AND ParaView_FOUND)
  paraview_plugin_scan(
    PLUGIN_FILES ${CMAKE_SOURCE_DIR}/filters/plugin/paraview.plugin
    PROVIDES_PLUGINS _tc_plugins
    ENABLE_BY_DEFAULT ON
    HIDE_PLUGINS_FROM_CACHE ON)
  paraview_plugin_build(
    PLUGINS ${_tc_plugins}
    RUNTIME_DESTINATION ${CMAKE_INSTALL_BINDIR}
    LIBRARY_DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY_SUBDIRECTORY trichart/plugins
    PLUGINS_FILE_NAME trichart.plugins.xml
    PLUGINS_COMPONENT plugins)
  set(TRICHART_PLUGIN_PATH
    "${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_LIBDIR}/trichart/plugins/TriChart/TriChart.so")
  set(TRICHART_PLUGIN_BUILD_PATH
    "${CMAKE_BINARY_DIR}/${CMAKE_INSTALL_LIBDIR}/trichart/plugins/TriChart/TriChart.so")
elseif (TRICHART_BUILD_PARAVIEW_PLUGIN)
  message(STATUS "TriChart: ParaView not found; the plugin is not built")
endif ()

# After the plugin, whose path the package's _config.py records.
if (TRICHART_WRAP_PYTHON)
  add_subdirectory(python)
endif ()

if (TRICHART_BUILD_APP)
  add_subdirectory(app)
endif ()

if (BUILD_TESTING)
  add_subdirectory(tests/vtk)
  if (TRICHART_WRAP_PYTHON)
    add_subdirectory(tests/python)
    add_subdirectory(tests/paraview)
    if (TRICHART_BUILD_APP)
      add_subdirectory(tests/app)
    endif ()
  endif ()
endif ()
