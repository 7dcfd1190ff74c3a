# Installation and the Debian package of the board daemon:
#   cmake --build <dir> --target tnv-fw tnv-board-emu && (cd <dir> && cpack -G DEB)
# The package holds tnv-fw, tnv-board-emu, the default config (a conffile)
# and the systemd unit (docs/install-board.md).
if(TARGET tnv-fw)
  # cpack / install use what is built: build tnv-fw and tnv-board-emu first, not the whole tree.
  set(CMAKE_SKIP_INSTALL_ALL_DEPENDENCY ON)
  # Every destination is relative, so `cmake --install --prefix P` writes
  # only under P. The package preset sets TNV_INSTALL_SYSCONFDIR=/etc: a
  # Debian package's configuration lives in /etc, not /usr/etc.
  set(TNV_INSTALL_SYSCONFDIR ${CMAKE_INSTALL_SYSCONFDIR} CACHE STRING
      "Where tnv-fw.toml goes (relative to the prefix, or absolute: /etc for the package)")
  install(TARGETS tnv-fw tnv-board-emu RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT board)
  install(FILES ${PROJECT_SOURCE_DIR}/packaging/tnv-fw.toml DESTINATION ${TNV_INSTALL_SYSCONFDIR}/tnv-fw COMPONENT board)
  install(FILES ${PROJECT_SOURCE_DIR}/packaging/tnv-fw.service DESTINATION lib/systemd/system COMPONENT board)
  install(FILES ${PROJECT_SOURCE_DIR}/packaging/tnv-fw.sysusers DESTINATION lib/sysusers.d RENAME tnv-fw.conf
          COMPONENT board)
  install(FILES ${PROJECT_SOURCE_DIR}/packaging/60-tnv-fw.rules DESTINATION lib/udev/rules.d COMPONENT board)
  install(FILES ${PROJECT_SOURCE_DIR}/docs/install-board.md ${PROJECT_SOURCE_DIR}/docs/hil-rig.md
          DESTINATION ${CMAKE_INSTALL_DATAROOTDIR}/doc/tnv-fw COMPONENT board)

  set(CPACK_PACKAGE_NAME "tnv-fw")
  set(CPACK_PACKAGE_VENDOR "TNV-40 project")
  set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "TNV-40 motion-control firmware daemon for a Linux board")
  set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
  set(CPACK_PACKAGING_INSTALL_PREFIX "/usr")
  set(CPACK_COMPONENTS_ALL board)
  set(CPACK_DEB_COMPONENT_INSTALL OFF)
  set(CPACK_DEBIAN_PACKAGE_MAINTAINER "TNV-40 firmware team <firmware@tnv40.invalid>")
  set(CPACK_DEBIAN_PACKAGE_SECTION "misc")
  set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # tnv-fw_<version>_<arch>.deb; arch from dpkg (amd64, arm64)
  set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
  set(CPACK_STRIP_FILES ON)
  # Cross builds (arm64): pass -DCPACK_DEBIAN_PACKAGE_ARCHITECTURE=arm64; dpkg-shlibdeps needs the arm64 libraries.
  set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA "${PROJECT_SOURCE_DIR}/packaging/conffiles;${PROJECT_SOURCE_DIR}/packaging/postinst")
  set(CPACK_GENERATOR "DEB")
  include(CPack)
endif()
