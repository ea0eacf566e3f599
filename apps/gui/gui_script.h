#pragma once
// gridtopo-gui's start: opens what the command line names and queues its scripted steps on the main frame.
#include "gui_arguments.h"
#include "main_frame.h"

namespace gridtopo::gui {

/// Opens the INI, topology INI, model (the shipped one by default), files and label image of `a` in `f`, applies
/// its view options, and queues its scripted steps in f->script (run the SLAM, save, use the SLAM map, topology,
/// view, click, benchmark, export, screenshot). Errors set f->exit_code = 1. The queued steps read `a` when they run:
/// it must live as long as the window (the app owns it).
void startGui(MainFrame* f, const GuiArguments& a);

}  // namespace gridtopo::gui
