package io.dtron.selenium.sample;

import io.dtron.api.IDtronChannelValued;
import io.dtron.selenium.AbstractSeleniumAdapter;
import io.dtron.selenium.ChannelVariables;
import jakarta.inject.Inject;
import jakarta.inject.Named;

/** Presses a button whose locator in the properties is wrong: input {@code i_press(user)}. */
@ChannelVariables("user")
public final class Press extends AbstractSeleniumAdapter {
    @Inject
    @Named("BASE_URL")
    String baseUrl;

    @Override
    protected void execute(IDtronChannelValued message) {
        getWebDriver().get(baseUrl + "/form");
        findElement("MISSING_BUTTON").click();
    }
}
