package io.dtron.selenium.sample;

import io.dtron.api.IDtronChannelValued;
import io.dtron.selenium.AbstractSeleniumAdapter;
import io.dtron.selenium.AdapterException;
import io.dtron.selenium.ChannelVariables;
import jakarta.inject.Inject;
import jakarta.inject.Named;

/** Types the user's name into the form, submits it and checks the greeting: input {@code i_greet(user)}. */
@ChannelVariables("user")
public final class Greet extends AbstractSeleniumAdapter {
    private final String baseUrl;

    /** Gets the site's address from the properties. */
    @Inject
    public Greet(@Named("BASE_URL") String baseUrl) {
        this.baseUrl = baseUrl;
    }

    /** Returns the address the adapter was given. */
    public String baseUrl() {
        return baseUrl;
    }

    @Override
    protected void execute(IDtronChannelValued message) {
        getWebDriver().get(baseUrl + "/form");
        findInput("Your name").sendKeys("user" + getUser());
        findElement("GO_BUTTON").click();
        requireGreeted();
    }

    /** The post-condition of a greeting: the page greets the current user. */
    public void requireGreeted() {
        String text = findElement("GREETING").getText();
        if (!text.equals("Hello user" + getUser())) {
            throw new AdapterException("the page says '" + text + "' to user " + getUser());
        }
    }
}
