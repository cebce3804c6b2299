package io.dtron.models.streetlight.adapters;

import io.dtron.api.IDtronChannelValued;
import io.dtron.selenium.AbstractSeleniumAdapter;
import io.dtron.selenium.ChannelVariables;
import jakarta.inject.Inject;
import jakarta.inject.Named;

/** {@code i_tick(user, controller)}: ticks the controller in the list and selects it. */
@ChannelVariables({"user", "controller"})
public final class Tick extends AbstractSeleniumAdapter {
    @Inject
    @Named("CONTROLLER_LABEL")
    String controllerLabel;

    @Override
    protected void execute(IDtronChannelValued message) {
        findInput(String.format(controllerLabel, message.getVariables().get("controller"))).click();
        findElement("SELECT_BUTTON").click();
        findElement("COMMAND_FORM");
    }
}
