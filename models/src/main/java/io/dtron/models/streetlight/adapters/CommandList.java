package io.dtron.models.streetlight.adapters;

import io.dtron.api.IDtronChannelValued;
import io.dtron.selenium.AbstractSeleniumAdapter;
import io.dtron.selenium.ChannelVariables;

/** {@code i_commandList(user)}: opens the list of light controllers from the menu. */
@ChannelVariables("user")
public final class CommandList extends AbstractSeleniumAdapter {

    @Override
    protected void execute(IDtronChannelValued message) {
        findElement("CONTROLLERS_LINK").click();
        findElement("CONTROLLER_LIST");
    }
}
