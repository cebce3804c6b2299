package io.dtron.models.streetlight.adapters;

import io.dtron.api.IDtronChannelValued;
import io.dtron.selenium.AbstractSeleniumAdapter;
import io.dtron.selenium.ChannelVariables;
import jakarta.inject.Inject;

/** {@code i_switch(user, state)}: chooses the new state of the selected controllers and switches. */
@ChannelVariables({"user", "state"})
public final class Switch extends AbstractSeleniumAdapter {
    @Inject
    StateLabels states;

    @Override
    protected void execute(IDtronChannelValued message) {
        findInput(states.label(message.getVariables().get("state"))).click();
        findElement("SWITCH_BUTTON").click();
        findElement("RESULT_STATUS");
    }
}
