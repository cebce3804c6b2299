package io.dtron.selenium.broken;

import io.dtron.api.IDtronChannelValued;
import io.dtron.selenium.AbstractSeleniumAdapter;
import io.dtron.selenium.ChannelVariables;

/** Input {@code i_crash(user)}: the user's browser goes away under the adapter (as a crashed browser would). */
@ChannelVariables("user")
public final class Crash extends AbstractSeleniumAdapter {
    @Override
    protected void execute(IDtronChannelValued message) {
        getWebDriver().quit();
        getWebDriver().getTitle();
    }
}
