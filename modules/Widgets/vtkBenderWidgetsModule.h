#ifndef vtkBenderWidgetsModule_h
#define vtkBenderWidgetsModule_h

// The Widgets module is a static library: no symbol export decoration is needed.
#define VTKBENDERWIDGETS_EXPORT

#endif
