package io.dtron.selenium.sample;

import io.dtron.api.IDtronChannelValued;
import io.dtron.selenium.AbstractSeleniumAdapter;
import io.dtron.selenium.ChannelVariables;
import jakarta.inject.Inject;
import jakarta.inject.Named;

/** Makes the site store a value in the user's cookie: input {@code i_remember(user, value)}. */
@ChannelVariables({"user", "value"})
public final class Remember extends AbstractSeleniumAdapter {
    @Inject
    @Named("BASE_URL")
    String baseUrl;

    @Override
    protected void execute(IDtronChannelValued message) {
        getWebDriver().get(baseUrl + "/set?v=" + message.getVariables().get("value"));
        findElement("id:stored");
    }
}
