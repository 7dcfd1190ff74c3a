# Installation of the programs, in two components that match the Debian
# packages (debian/, built by scripts/package.sh):
#   board  tnv-fw, its default config, the units, udev rules, sysusers, docs
#   tools  tnvctl, tnv-hil, tnv-board-emu (the host side and the bench rig)
# `cmake --install <dir> --component board --prefix P` writes only under P.
if(TARGET tnv-fw)
  # install uses what is built: build the programs first, not the whole tree.
  set(CMAKE_SKIP_INSTALL_ALL_DEPENDENCY ON)
  # Every destination is relative, so `cmake --install --prefix P` writes
  # only under P. The package preset sets TNV_INSTALL_SYSCONFDIR=/etc: a
  # Debian package's configuration lives in /etc, not /usr/etc.
  set(TNV_INSTALL_SYSCONFDIR ${CMAKE_INSTALL_SYSCONFDIR} CACHE STRING
      "Where tnv-fw.toml goes (relative to the prefix, or absolute: /etc for the package)")
  install(TARGETS tnv-fw RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT board)
  install(FILES ${PROJECT_SOURCE_DIR}/packaging/tnv-fw.toml DESTINATION ${TNV_INSTALL_SYSCONFDIR}/tnv-fw COMPONENT board)
  install(FILES ${PROJECT_SOURCE_DIR}/packaging/tnv-fw.service ${PROJECT_SOURCE_DIR}/packaging/tnv-fw@.service
          DESTINATION lib/systemd/system COMPONENT board)
  install(FILES ${PROJECT_SOURCE_DIR}/packaging/tnv-fw.sysusers DESTINATION lib/sysusers.d RENAME tnv-fw.conf
          COMPONENT board)
  install(FILES ${PROJECT_SOURCE_DIR}/packaging/60-tnv-fw.rules DESTINATION lib/udev/rules.d COMPONENT board)
  install(FILES ${PROJECT_SOURCE_DIR}/docs/install-board.md ${PROJECT_SOURCE_DIR}/docs/hil-rig.md
          DESTINATION ${CMAKE_INSTALL_DATAROOTDIR}/doc/tnv-fw COMPONENT board)
  install(TARGETS tnv-board-emu RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT tools)
endif()
foreach(t tnvctl tnv-hil)
  if(TARGET ${t})
    install(TARGETS ${t} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT tools)
  endif()
endforeach()
# The Python module joins the tools component (and the tnv-tools package)
# once it is built.
