#ifndef vtkBenderFiltersModule_h
#define vtkBenderFiltersModule_h

// The Filters module is a static library: no symbol export decoration is needed.
#define VTKBENDERFILTERS_EXPORT

#endif
