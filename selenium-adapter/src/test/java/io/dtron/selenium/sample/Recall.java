package io.dtron.selenium.sample;

import io.dtron.api.IDtronChannelValued;
import io.dtron.selenium.AbstractSeleniumAdapter;
import io.dtron.selenium.ChannelVariables;
import jakarta.inject.Inject;
import jakarta.inject.Named;

/** Reads the value the site keeps for the user and reports it as the result code: input {@code i_recall(user)}. */
@ChannelVariables("user")
public final class Recall extends AbstractSeleniumAdapter {
    @Inject
    @Named("BASE_URL")
    String baseUrl;

    @Override
    protected void execute(IDtronChannelValued message) {
        getWebDriver().get(baseUrl + "/get");
        reportResult(Integer.parseInt(findElement("VALUE").getText()));
    }
}
