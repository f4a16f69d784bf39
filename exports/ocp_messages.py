"""OpenCASCADE's messages kept off stdout, for every module that calls it (STEP read and write)."""


def quiet_ocp() -> None:
    """Keep only failures of OpenCASCADE's default messenger, which prints banners on stdout.

    The stdout of a --json command must hold the JSON alone.
    """
    from OCP.Message import Message, Message_Gravity

    for printer in Message.DefaultMessenger_s().Printers():
        printer.SetTraceLevel(Message_Gravity.Message_Fail)
