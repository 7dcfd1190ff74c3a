"""The Program panel as its browser tests open it: the page under control,
the scope paused (it need not redraw meanwhile), the panel in view; and the
page's program state as the node reported it."""

from test_tuning_page import open_page, page_value, take_control


def open_program_tab(server, browsers):
    b = browsers()
    open_page(b, server)
    b.find_element("id", "pause").click()
    take_control(b)
    b.execute_script("document.getElementById('program-section').scrollIntoView();")
    return b


def program_state(b):
    return page_value(b, "window.tnvPage.program")
