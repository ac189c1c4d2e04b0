# Documentation install and the Debian package (CPack, DEB generator). Included at the end of the
# top-level CMakeLists.txt, after every install() rule, because include(CPack) reads them all.
#
#   cmake --install build --prefix /tmp/oscilab    # a tree: bin/, share/applications, ...
#   cd build && cpack -G DEB                        # oscilab_VERSION_ARCH.deb, installs in /usr

install(FILES README.md DESTINATION share/doc/oscilab)
install(DIRECTORY docs/ DESTINATION share/doc/oscilab/docs
  FILES_MATCHING PATTERN "*.md" PATTERN "*.png" PATTERN "*.csv")

set(OSCILAB_DEB_MAINTAINER "Oscilab maintainers <oscilab@localhost>" CACHE STRING
  "Maintainer field of the Debian package (Name <email>)")

set(CPACK_PACKAGE_NAME oscilab)
set(CPACK_PACKAGE_VENDOR "Oscilab")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
  "lab tool for testing nonlinear oscillators on a shaking table")
set(CPACK_PACKAGE_CONTACT "${OSCILAB_DEB_MAINTAINER}")
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)

set(CPACK_DEBIAN_PACKAGE_MAINTAINER "${OSCILAB_DEB_MAINTAINER}")
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # oscilab_0.1.0_amd64.deb
# The extended description; CPack puts the summary above it as the synopsis and indents each
# line as Debian Policy §5.6.13 asks.
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION "Oscilab records, analyses and identifies strongly nonlinear (bistable) oscillators
tested on a shaking table: the desktop app (oscilab) and a command line
(oscilab-cli) for simulation with a virtual rig, measurement analysis (energy
dissipated per cycle, restoring force), harmonic balance with continuation,
friction identification and model-gap diagnosis, and export to MATLAB and UFF 58.")
# Depends from the shared libraries the binaries link (dpkg-shlibdeps, in dpkg-dev).
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# The Python module (python/) links no libpython, so dpkg-shlibdeps cannot see what it needs: the
# interpreter it was built for (its extension suffix names the minor version) and NumPy.
if(OSCILAB_PYTHON)
  math(EXPR python_next_minor "${Python3_VERSION_MINOR} + 1")
  set(CPACK_DEBIAN_PACKAGE_DEPENDS "python3 (>= ${Python3_VERSION_MAJOR}.${Python3_VERSION_MINOR}), \
python3 (<< ${Python3_VERSION_MAJOR}.${python_next_minor}), python3-numpy")
endif()

include(CPack)
